// LightsFromFile: a dome capture's own .lp file gives the lights, instead of SphereDetection,
// HighlightDetection and LightDirections. Writes assembly-files/lights.lp (the images named
// relative to it) and puts kLights (stages/inputs.h). With the dome's radius stated
// (lightDistance, frame widths: relight-cli's -3), each light is placed at that distance from
// the frame's centre along its direction (kLightPlaces, nearLight items, lights.dome).
#pragma once

#include <string>
#include <utility>

#include "pipeline/stage.h"

namespace surrogate::stages {

// The parameters of LightsFromFile; their names are what carriers record.
struct LightsFromFileOptions {
  // "auto" or "infinity": the lights at infinity (directions); a number: frame widths from the
  // frame's centre (StatedDistance; a length with a unit is refused: a dome has no spheres to
  // give the frame's scale).
  std::string lightDistance = "auto";

  pipeline::Parameters toParameters() const;
  // Error(Input) for an unknown name, Error(Usage) for a distance that is not one.
  static LightsFromFileOptions fromParameters(const pipeline::Parameters& parameters);
};

class LightsFromFileStage : public pipeline::DescribedStage<LightsFromFileStage> {
 public:
  static constexpr const char* kComponent = "LightsFromFile";
  static pipeline::StageInfo info();
  void run(const carrier::Step&, pipeline::Context&, carrier::Result&) override;
};

}  // namespace surrogate::stages
