// How well a basis relights lights it never saw, measured on the capture itself: K photographs
// are left out (fit/held_out.h chooseHeldOut), the model is fitted on the others exactly as it
// would be on all, and relit at the left-out lights as a viewer shows it (a learned model through
// its JPEG planes; a .ptm or .rti as stored), then compared with the photographs (PSNR, SSIM).
// The blend of the three nearest photographs is measured beside it: the figure any model should
// beat (docs/hrti-math.md, "Quality at unseen lights").
//
//   ModelRecipe recipe;  recipe.basis = "bln";  recipe.learned.planes = 45;
//   HeldOutQuality q = measureHeldOut(stack, lights, recipe, 6);
//   // q.model.psnr, q.model.ssim, q.nearestBlend.psnr, q.perLight[i] at lights[q.indices[i]]
#pragma once

#include <array>
#include <string>
#include <vector>

#include "core/stack.h"
#include "fit/fit.h"
#include "fit/held_out.h"
#include "fit/learned.h"
#include "publish/web_layout.h"

namespace surrogate::stages {

// What is fitted: `basis` is one of fit/basis.h's names (ptm-lrgb, ptm-rgb, hsh2, hsh3) or a
// learned one (rbf, bln), with the options of its kind; `web` the learned planes' JPEG qualities.
struct ModelRecipe {
  std::string basis = "bln";
  fit::LearnedOptions learned;
  publish::PublishOptions web;
  int threads = 0;
};

struct HeldOutQuality {
  std::vector<int> indices;                 // the photographs left out, in stack order
  std::vector<fit::HeldOutScore> perLight;  // the model at each of them
  fit::HeldOutScore model;                  // pooled (fit/held_out.h meanScore)
  fit::HeldOutScore nearestBlend;           // the three nearest photographs, pooled
};

// Error(Usage) naming "--holdout K" unless 1 <= K <= N - 4: a fit keeps at least 4 photographs.
// What fit, run and measureHeldOut check, before any work where they can.
void checkHoldoutCount(int count, int photographs);

// Throws what the fit throws (too few photographs left for the basis, ...) and
// checkHoldoutCount's error.
HeldOutQuality measureHeldOut(const ImageStack& stack, const std::vector<std::array<double, 3>>& lights,
                              const ModelRecipe& recipe, int count);

// A learned model as a viewer reads it: its planes through the JPEG compression `web` asks for.
fit::LearnedModel learnedAsViewed(const fit::LearnedModel& model, const publish::PublishOptions& web);
// The same from the layout already made of it (publish::webLayoutOf, whole planes): its JPEGs
// decoded, not encoded again.
fit::LearnedModel learnedAsViewed(const fit::LearnedModel& model, const publish::WebLayoutFiles& layout);

}  // namespace surrogate::stages
