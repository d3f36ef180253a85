// SphereDetection: per-pixel median of the luminance stack (reduced, and at full resolution
// around the spheres), circle Hough, sub-pixel refinement; or the user's circles (intervention
// manual-sphere). Writes assembly-files/spheres.png (the detection drawn on the reduced
// median). Puts kSpheres and kStackMedian (stages/inputs.h). The mathematics:
// docs/hrti-math.md.
#pragma once

#include "pipeline/stage.h"

namespace surrogate::stages {

class SphereDetectionStage : public pipeline::DescribedStage<SphereDetectionStage> {
 public:
  static constexpr const char* kComponent = "SphereDetection";
  static pipeline::StageInfo info();
  void run(const carrier::Step&, pipeline::Context&, carrier::Result&) override;
};

}  // namespace surrogate::stages
