// What the stages hand to the stages after them, through the pipeline context: the
// blackboard keys (ctx.put, ctx.get) and what the ingest stage puts.
#pragma once

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

// One photograph the pipeline uses (after exclusions), in capture order.
struct InputImage {
  std::string fileId;        // in the carrier's files section
  std::string relativePath;  // to the capture root
  std::string stem;          // the shot's name
};
using InputImages = std::vector<InputImage>;

}  // namespace surrogate::stages
