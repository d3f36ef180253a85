// Quality at lights a model never saw: a photograph left out of the fit is compared with the
// model relit at that photograph's light (docs/hrti-math.md, "Quality at unseen lights").
//
//   std::vector<int> out = chooseHeldOut(lights, 6);      // which photographs to leave out
//   ... fit on the others, relight at lights[out[i]] ...
//   HeldOutScore s = compareImages(relit, photograph);     // PSNR and SSIM of one pair
//
// PSNR: over every pixel and the three channels, in 8-bit units of the stored (sRGB-encoded)
// values, 20 log10(255 / rmse), capped at 100 dB. SSIM: Wang et al. 2004 with their constants
// (Gaussian window sigma 1.5, K1 0.01, K2 0.03, L 255), the mean over the image of each channel,
// then over the channels. A set's figure is the PSNR of the pooled mean squared error and the mean
// SSIM (meanScore).
#pragma once

#include <array>
#include <vector>

#include "core/image.h"
#include "core/stack.h"

namespace surrogate::fit {

struct HeldOutScore {
  double psnr = 0;
  double ssim = 0;
  double mse = 0;  // in 8-bit units squared, for pooling
};

// Both images RGB (or both grey), same size; 8- or 16-bit samples (16-bit read as value / 257).
// Error(Internal) when they differ in size or channels.
HeldOutScore compareImages(const Image& rendered, const Image& photograph);

// The pooled figure of several pairs: PSNR of the mean of the MSEs, mean of the SSIMs.
HeldOutScore meanScore(const std::vector<HeldOutScore>& scores);

// `count` photographs to leave out, spread over the light directions: deterministic (farthest
// point sampling in angle, starting from the light nearest the lights' mean direction, ties to
// the lower index), returned in increasing index order. 0 < count < lights.size(), else
// Error(Usage) naming "--holdout".
std::vector<int> chooseHeldOut(const std::vector<std::array<double, 3>>& lights, int count);

// The baseline every model should beat at an unseen light: the `count` photographs whose lights
// are nearest in angle to `light`, blended with weights proportional to 1 / (angle + 1e-6)
// (normalised). `lights` in stack order. Output as renderLearned's (8-bit widened, RGB).
Image nearestPhotographBlend(const ImageStack& stack, const std::vector<std::array<double, 3>>& lights,
                             const std::array<double, 3>& light, int count = 3);

}  // namespace surrogate::fit
