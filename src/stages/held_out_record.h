// A fit step's quality at lights left out (stages/held_out_quality.h), measured and recorded the
// same way by RtiFit and LearnedFit: `heldOutImages`, `heldOutPsnr` (dB), `heldOutSsim`,
// `nearestBlendPsnr` (dB), `nearestBlendSsim` as values, the PSNR and SSIM of each photograph
// left out as imageValues, and one line of the log (docs/carrier.md, the fit steps).
//
//   if (holdout > 0) measureAndRecordHeldOut(step, ctx, result, recipe, *rgb, *lights, holdout);
#pragma once

#include <array>
#include <vector>

#include "carrier/carrier.h"
#include "core/stack.h"
#include "pipeline/context.h"
#include "stages/held_out_quality.h"

namespace surrogate::stages {

// Error(Input) naming the recorded parameter holdout=K when the photographs cannot spare K.
void measureAndRecordHeldOut(const carrier::Step& step, pipeline::Context& ctx, carrier::Result& result,
                             const ModelRecipe& recipe, const ImageStack& rgb,
                             const std::vector<std::array<double, 3>>& lights, int holdout);

}  // namespace surrogate::stages
