// HighlightDetection: the specular highlight on each sphere in each image, judged (flag,
// confidence 0..1 and the reason when refused or doubtful, see hrti/highlight_detection.h);
// manual-highlight interventions override single images. Refuses (Error(Input)) an image with
// no trustworthy highlight on any sphere, naming it and what to do (--exclude or --highlight),
// and a sphere without one in most images (the circle is not on a sphere: --sphere,
// --forget-sphere, --sphere-roi), both as hrti::HighlightRefusal (the review page words them
// itself). Writes one overview per sphere
// (assembly-files/highlights-sphereN.png). Puts kHighlights (stages/inputs.h).
#pragma once

#include "pipeline/stage.h"

namespace surrogate::stages {

class HighlightDetectionStage : public pipeline::DescribedStage<HighlightDetectionStage> {
 public:
  static constexpr const char* kComponent = "HighlightDetection";
  static pipeline::StageInfo info();
  void run(const carrier::Step&, pipeline::Context&, carrier::Result&) override;
};

}  // namespace surrogate::stages
