// WhiteBalance: per-channel gains in linear light: as shot (none beyond the decoder's), from a
// grey region (median over the stack of the region's per-image means, G = 1), or given
// multipliers; then the fit's input encoding (srgb or linear). Records the gains, per-image
// region means and the output space. Parameters: WhiteBalanceOptions (stages/preprocess.h).
// A pre-processing stage (the family: stages/preprocess_steps.h): it replaces the
// "rgb-stack" the fit reads with a view computed on demand, never the files, never what the
// light estimation reads.
#pragma once

#include "pipeline/stage.h"

namespace surrogate::stages {

class WhiteBalanceStage : public pipeline::DescribedStage<WhiteBalanceStage> {
 public:
  static constexpr const char* kComponent = "WhiteBalance";
  static pipeline::StageInfo info();
  void run(const carrier::Step&, pipeline::Context&, carrier::Result&) override;
};

}  // namespace surrogate::stages
