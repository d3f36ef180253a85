// Crop: a rectangle given by the user, or the largest one clear of the spheres the
// SphereDetection step recorded (with a margin). Records the rectangle and how it was chosen.
// Parameters: CropOptions (stages/preprocess.h).
// A pre-processing stage (the family: stages/preprocess_steps.h): it replaces the
// "rgb-stack" the fit reads with a view computed on demand, never the files, never what the
// light estimation reads.
#pragma once

#include "pipeline/stage.h"

namespace surrogate::stages {

class CropStage : public pipeline::DescribedStage<CropStage> {
 public:
  static constexpr const char* kComponent = "Crop";
  static pipeline::StageInfo info();
  void run(const carrier::Step&, pipeline::Context&, carrier::Result&) override;
};

}  // namespace surrogate::stages
