// LightsFromFile: a dome capture's own .lp file gives the lights, instead of SphereDetection,
// HighlightDetection and LightDirections. Writes assembly-files/lights.lp (the images named
// relative to it) and puts kLights (stages/inputs.h).
#pragma once

#include "pipeline/stage.h"

namespace surrogate::stages {

class LightsFromFileStage : public pipeline::DescribedStage<LightsFromFileStage> {
 public:
  static constexpr const char* kComponent = "LightsFromFile";
  static pipeline::StageInfo info();
  void run(const carrier::Step&, pipeline::Context&, carrier::Result&) override;
};

}  // namespace surrogate::stages
