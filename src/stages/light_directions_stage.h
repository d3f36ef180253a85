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
  // How far the lights were from the object (docs/hrti-math.md, "Near lights"): "auto", not
  // stated (two spheres place a light where they can); "infinity": every light a direction;
  // a number: frame widths from the frame's centre (relight's dome ratio); a length with a unit
  // ("1.2m", "800mm", "90cm"): needs sphereDiameterMm, which gives the frame's scale.
  std::string lightDistance = "auto";

  pipeline::Parameters toParameters() const;
  // Missing names keep their defaults. Error(Usage) for an unknown model; Error(Input) naming
  // the parameter for an unknown name or a length that is not a finite number >= 0.
  static LightDirectionsOptions fromParameters(const pipeline::Parameters& parameters);
  // One field as toParameters() writes it (what the command line records when it sets only
  // that field): parameter(&LightDirectionsOptions::focalLengthMm), or the model's.
  std::pair<std::string, std::string> parameter(double LightDirectionsOptions::*length) const;
  std::pair<std::string, std::string> modelParameter() const;
  std::pair<std::string, std::string> lightDistanceParameter() const;
};

// The range of a light distance in frame widths: closer than half a width the light would
// stand over the object; past 1000 widths it is at infinity for any fit.
inline constexpr double kMinLightDistanceWidths = 0.5, kMaxLightDistanceWidths = 1000;

// A stated light distance read: infinity, frame widths, or millimetres. Error(Usage) naming
// `where` for any other text ("2 m" with a space is refused: one word).
struct StatedDistance {
  enum class Kind { Auto, Infinity, FrameWidths, Millimetres } kind = Kind::Auto;
  double value = 0;  // frame widths or millimetres
  static StatedDistance parse(const std::string& text, const std::string& where);
};

class LightDirectionsStage : public pipeline::DescribedStage<LightDirectionsStage> {
 public:
  static constexpr const char* kComponent = "LightDirections";
  static pipeline::StageInfo info();
  void run(const carrier::Step&, pipeline::Context&, carrier::Result&) override;
};

}  // namespace surrogate::stages
