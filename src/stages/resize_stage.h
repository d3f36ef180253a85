// Resize: a scale factor or a target size, area averaging in linear light with exact integer
// weights. Records the input and output sizes and the filter. Parameters: ResizeOptions
// (stages/preprocess.h).
// A pre-processing stage (the family: stages/preprocess_steps.h): it replaces the
// "rgb-stack" the fit reads with a view computed on demand, never the files, never what the
// light estimation reads.
#pragma once

#include "pipeline/stage.h"

namespace surrogate::stages {

class ResizeStage : public pipeline::DescribedStage<ResizeStage> {
 public:
  static constexpr const char* kComponent = "Resize";
  static pipeline::StageInfo info();
  void run(const carrier::Step&, pipeline::Context&, carrier::Result&) override;
};

}  // namespace surrogate::stages
