// What the stages hand to the stages after them, through the pipeline context: the
// blackboard keys (ctx.put, ctx.get) and what the ingest stage puts.
#pragma once

#include <array>
#include <filesystem>
#include <memory>
#include <string>
#include <vector>

#include "core/stack.h"

namespace surrogate::stages {

// Blackboard keys.
inline constexpr const char* kInputImages = "input-images";
inline constexpr const char* kRgbStack = "rgb-stack";
// The decoded stack as ImageDecode made it: kRgbStack before any pre-processing step replaced
// it (the Audit compares another tool's result with the whole frames).
inline constexpr const char* kDecodedRgbStack = "decoded-rgb-stack";
inline constexpr const char* kLuminanceStack = "luminance-stack";
// The light estimation's (SphereDetection, HighlightDetection, LightDirections, LightsFromFile).
inline constexpr const char* kSpheres = "spheres";
inline constexpr const char* kStackMedian = "stack-median";  // hrti::StackMedian
inline constexpr const char* kHighlights = "highlights";
inline constexpr const char* kLights = "lights";
// Where each light was (LightDirections, LightsFromFile): LightPlaces. Absent or all far: every
// light at infinity.
inline constexpr const char* kLightPlaces = "light-places";
// How the pixels of kRgbStack lie in the full frame the lights were measured in (StackFrame):
// ImageDecode puts the identity, Crop and Resize compose theirs.
inline constexpr const char* kStackFrame = "stack-frame";

// One photograph the pipeline uses (after exclusions), in capture order.
struct InputImage {
  std::string fileId;        // in the carrier's files section
  std::string relativePath;  // to the capture root
  std::string stem;          // the shot's name
};
using InputImages = std::vector<InputImage>;

// The index of the image `name` names: its shot name, or a file name or path whose stem is the
// shot's (what an option or an intervention gives); -1 when none does.
inline int inputIndexOf(const InputImages& inputs, const std::string& name) {
  const std::string stem = std::filesystem::path(name).stem().string();
  for (std::size_t i = 0; i < inputs.size(); ++i)
    if (inputs[i].stem == stem || inputs[i].stem == name) return static_cast<int>(i);
  return -1;
}

// One light's place, in the frame coordinates of docs/hrti-math.md ("Near lights"): pixels of
// the full frame, origin at the frame's centre on the object's plane, x right, y up, z towards
// the camera. `near` false: the light is at infinity (a direction only).
struct LightPlace {
  bool near = false;
  std::array<double, 3> position{};
};
struct LightPlaces {
  int frameWidth = 0, frameHeight = 0;  // the full frame, pixels
  std::vector<LightPlace> lights;       // one per input image, in order
  bool anyNear() const {
    for (const LightPlace& l : lights)
      if (l.near) return true;
    return false;
  }
};

// Full-frame pixel (u, v) of the stack's pixel (x, y): u = x0 + sx x, v = y0 + sy y (pixel
// centres; a resize by f maps a pixel's centre to the centre of the f x f block it averages).
struct StackFrame {
  int fullWidth = 0, fullHeight = 0;
  double x0 = 0, y0 = 0, sx = 1, sy = 1;
};

}  // namespace surrogate::stages
