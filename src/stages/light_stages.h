// The light-estimation stages (the mathematics: docs/hrti-math.md):
//
//   SphereDetection     per-pixel median of the luminance stack, circle Hough, sub-pixel
//                       refinement; or the user's circles (intervention manual-sphere).
//                       Writes assembly-files/spheres.png (the detection drawn on the median).
//   HighlightDetection  the specular highlight on each sphere in each image, judged (flag,
//                       confidence 0..1 and the reason when refused or doubtful, see
//                       hrti/highlight_detection.h); manual-highlight interventions override
//                       single images. Refuses (Error(Input)) an image with no trustworthy
//                       highlight on any sphere, naming it and what to do (--exclude or
//                       --highlight), and a sphere without one in most images (the circle is
//                       not on a sphere: --sphere, --forget-sphere, --sphere-roi). Writes one
//                       overview per sphere (assembly-files/highlights-sphereN.png).
//   LightDirections     the reflection formula per sphere (orthographic, or perspective with
//                       the camera's focal length and pixel pitch), averaged over spheres;
//                       3D light positions when two spheres and their diameter are known.
//                       Writes assembly-files/lights.lp.
//   LightsFromFile      a dome capture's own .lp file instead of the three stages above.
#pragma once

#include "pipeline/stage.h"

namespace surrogate::stages {

inline constexpr const char* kSpheres = "spheres";
inline constexpr const char* kMedianImage = "median-image";
inline constexpr const char* kHighlights = "highlights";
inline constexpr const char* kLights = "lights";

class SphereDetectionStage : public pipeline::Stage {
 public:
  std::string component() const override { return "SphereDetection"; }
  std::string version() const override { return "1"; }
  void run(const carrier::Step&, pipeline::Context&, carrier::Result&) override;
};

class HighlightDetectionStage : public pipeline::Stage {
 public:
  std::string component() const override { return "HighlightDetection"; }
  // 2: every highlight judged (confidence, reason, refused flags), refusals stop the run
  std::string version() const override { return "2"; }
  void run(const carrier::Step&, pipeline::Context&, carrier::Result&) override;
};

class LightDirectionsStage : public pipeline::Stage {
 public:
  std::string component() const override { return "LightDirections"; }
  std::string version() const override { return "2"; }  // 2: lights.lp names images relative to its own folder
  void run(const carrier::Step&, pipeline::Context&, carrier::Result&) override;
};

class LightsFromFileStage : public pipeline::Stage {
 public:
  std::string component() const override { return "LightsFromFile"; }
  std::string version() const override { return "2"; }  // 2: lights.lp names images relative to its own folder
  void run(const carrier::Step&, pipeline::Context&, carrier::Result&) override;
};

}  // namespace surrogate::stages
