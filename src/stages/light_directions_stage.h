// LightDirections: the reflection formula per sphere (orthographic, or perspective with the
// camera's focal length and pixel pitch), averaged over spheres; 3D light positions when two
// spheres and their diameter are known; then the checks of hrti/light_checks.h, each recorded
// (item `check`): a failed one stops the run unless accepted (intervention accept-check,
// `--accept CHECK --reason`, stages/recorded_checks.h). Writes assembly-files/lights.lp and
// puts kLights (stages/inputs.h). The mathematics: docs/hrti-math.md.
#pragma once

#include <string>
#include <utility>

#include "pipeline/stage.h"

namespace surrogate::stages {

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

class LightDirectionsStage : public pipeline::DescribedStage<LightDirectionsStage> {
 public:
  static constexpr const char* kComponent = "LightDirections";
  static pipeline::StageInfo info();
  void run(const carrier::Step&, pipeline::Context&, carrier::Result&) override;
};

}  // namespace surrogate::stages
