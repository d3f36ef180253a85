// A learned model (fit/learned.h: relight's RBF and bilinear bases) behind the Relightable
// interface of fit/render.h, so that `surrogate render` relights a learned web layout as it
// relights a .ptm, an .rti or their layouts.
//
//   render:     renderLearned at the light, as OpenLIME draws it;
//   --gain, --specular: refused (Error(Usage) naming the option): a learned basis has no
//               closed-form normal or polynomial to enhance around;
//   normals:    a least-squares Lambertian fit b = rho n of the model as the viewer computes it
//               (values 0..1 before the viewer's clamp, so that b is linear in the texel's
//               bytes) at fit/lambert.h's 61 directions (those of every model), the mean of
//               the three channels' b; (0, 0, 1) where b is 0 or faces away;
//   albedo:     the model at that normal (0..255 units, as the PTM's and HSH's albedo); for rbf
//               the weights at the normal come from a 65 x 65 table over the octahedral map.
//
//   auto model = fit::makeRelightable(std::move(web.learned));
//   Image relit = model->render({0.3, 0.2, 0.93}, {});
#pragma once

#include <memory>

#include "fit/learned.h"
#include "fit/render.h"

namespace surrogate::fit {

std::unique_ptr<Relightable> makeRelightable(LearnedModel model);

}  // namespace surrogate::fit
