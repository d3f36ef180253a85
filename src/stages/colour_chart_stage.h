// ColourCorrection: colour from a chart in the frame. Finds a ColorChecker Classic (or takes
// its corners given by hand), measures its patches in linear light (in every frame, at the
// light along its normal: stages/chart_measurement.h; or in the one image named), fits a
// correction to the chart's reference values (colour/correction_model.h), and replaces the
// "rgb-stack" the fit reads with the corrected view (stages/colour_stack.h); never the files,
// never what light estimation reads. Records the chart's place, the reference (its edition),
// the model's coefficients, per patch the reference, the measurement and CIEDE2000 before and
// after, the mean and max, and the FADGI and Metamorfoze levels they reach.
//
// Planned by `surrogate run` after light estimation and before pre-processing (the Colour
// slot), with chart=auto: a capture without a chart keeps its colours, bit for bit.
// Parameters: ColourChartOptions (stages/colour_chart_options.h).
#pragma once

#include "pipeline/stage.h"

namespace surrogate::stages {

class ColourChartStage : public pipeline::DescribedStage<ColourChartStage> {
 public:
  static constexpr const char* kComponent = "ColourCorrection";
  static pipeline::StageInfo info();
  void run(const carrier::Step&, pipeline::Context&, carrier::Result&) override;
};

}  // namespace surrogate::stages
