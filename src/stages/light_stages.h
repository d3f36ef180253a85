// The light-estimation stages (the mathematics: docs/hrti-math.md):
//
//   SphereDetection     per-pixel median of the luminance stack (reduced, and at full
//                       resolution around the spheres), circle Hough, sub-pixel refinement; or
//                       the user's circles (intervention manual-sphere). Writes
//                       assembly-files/spheres.png (the detection drawn on the reduced median).
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
//                       3D light positions when two spheres and their diameter are known;
//                       then the checks of hrti/light_checks.h, each recorded (item `check`):
//                       a failed one stops the run unless accepted (intervention accept-check,
//                       `--accept CHECK --reason`). Writes assembly-files/lights.lp.
//   LightsFromFile      a dome capture's own .lp file instead of the three stages above.
//
// Each stage's info() (version, description, place in the plan, parameters) is defined next to
// its run() in light_stages.cpp.
#pragma once

#include <string>
#include <utility>

#include "pipeline/stage.h"

namespace surrogate::stages {

inline constexpr const char* kSpheres = "spheres";
inline constexpr const char* kStackMedian = "stack-median";  // hrti::StackMedian
inline constexpr const char* kHighlights = "highlights";
inline constexpr const char* kLights = "lights";
// The intervention that accepts a failed check on the lights by name (--accept CHECK).
inline constexpr const char* kAcceptCheck = "accept-check";

// The parameters of LightDirections. Their names and values are what carriers record: never
// rename them. Lengths are millimetres; 0 means "not given".
struct LightDirectionsOptions {
  // "orthographic": each sphere seen along the optical axis (needs no lens data; good for
  // spheres near the image centre or a long lens). "perspective": the ray through each
  // highlight from the focal length and pixel pitch (better for spheres far off-centre with a
  // short lens; needs both, from these values or the EXIF).
  std::string model = "orthographic";
  double focalLengthMm = 0;     // 0: the first image's EXIF focal length
  double pixelPitchMm = 0;      // 0: from the EXIF focal-plane resolution
  double sphereDiameterMm = 0;  // with two spheres and the lens known: light positions; 0: none

  pipeline::Parameters toParameters() const;
  // Missing names keep their defaults. Error(Usage) for an unknown model; Error(Input) naming
  // the parameter for an unknown name or a length that is not a finite number >= 0.
  static LightDirectionsOptions fromParameters(const pipeline::Parameters& parameters);
  // One field as toParameters() writes it (what the command line records when it sets only
  // that field): parameter(&LightDirectionsOptions::focalLengthMm), or the model's.
  std::pair<std::string, std::string> parameter(double LightDirectionsOptions::*length) const;
  std::pair<std::string, std::string> modelParameter() const;
};

class SphereDetectionStage : public pipeline::DescribedStage<SphereDetectionStage> {
 public:
  static constexpr const char* kComponent = "SphereDetection";
  static pipeline::StageInfo info();
  void run(const carrier::Step&, pipeline::Context&, carrier::Result&) override;
};

class HighlightDetectionStage : public pipeline::DescribedStage<HighlightDetectionStage> {
 public:
  static constexpr const char* kComponent = "HighlightDetection";
  static pipeline::StageInfo info();
  void run(const carrier::Step&, pipeline::Context&, carrier::Result&) override;
};

class LightDirectionsStage : public pipeline::DescribedStage<LightDirectionsStage> {
 public:
  static constexpr const char* kComponent = "LightDirections";
  static pipeline::StageInfo info();
  void run(const carrier::Step&, pipeline::Context&, carrier::Result&) override;
};

class LightsFromFileStage : public pipeline::DescribedStage<LightsFromFileStage> {
 public:
  static constexpr const char* kComponent = "LightsFromFile";
  static pipeline::StageInfo info();
  void run(const carrier::Step&, pipeline::Context&, carrier::Result&) override;
};

}  // namespace surrogate::stages
