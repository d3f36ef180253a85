#include "stages/held_out_record.h"

#include "core/error.h"
#include "core/text.h"
#include "stages/inputs.h"

namespace surrogate::stages {

void measureAndRecordHeldOut(const carrier::Step& step, pipeline::Context& ctx, carrier::Result& result,
                             const ModelRecipe& recipe, const ImageStack& rgb,
                             const std::vector<std::array<double, 3>>& lights, int holdout) {
  ctx.progress("Fitting " + recipe.basis + " without " + std::to_string(holdout) + " photographs", 0);
  HeldOutQuality q;
  try {
    q = measureHeldOut(rgb, lights, recipe, holdout);
  } catch (const Error& e) {  // the recorded parameter, not the command line's option
    throw Error(ErrorKind::Input, "holdout=" + std::to_string(holdout), step.component, e.message());
  }
  const auto inputs = ctx.get<InputImages>(kInputImages);
  result.add("value").set("name", "heldOutImages").set("value", std::to_string(q.indices.size()));
  result.add("value").set("name", "heldOutPsnr").set("value", formatNumber(q.model.psnr)).set("unit", "dB");
  result.add("value").set("name", "heldOutSsim").set("value", formatNumber(q.model.ssim));
  result.add("value").set("name", "nearestBlendPsnr").set("value", formatNumber(q.nearestBlend.psnr)).set("unit", "dB");
  result.add("value").set("name", "nearestBlendSsim").set("value", formatNumber(q.nearestBlend.ssim));
  for (std::size_t i = 0; i < q.indices.size(); ++i) {
    const std::string image = (*inputs)[q.indices[i]].fileId;
    result.add("imageValue").set("image", image).set("name", "heldOutPsnr")
        .set("value", formatNumber(q.perLight[i].psnr)).set("unit", "dB");
    result.add("imageValue").set("image", image).set("name", "heldOutSsim")
        .set("value", formatNumber(q.perLight[i].ssim));
  }
  ctx.carrier.addLog("info", step.id,
                     recipe.basis + " at " + std::to_string(q.indices.size()) + " lights left out of the fit: PSNR " +
                         fixedDecimals(q.model.psnr, 2) + " dB, SSIM " + fixedDecimals(q.model.ssim, 3) +
                         " (the 3 nearest photographs blended: " + fixedDecimals(q.nearestBlend.psnr, 2) +
                         " dB, SSIM " + fixedDecimals(q.nearestBlend.ssim, 3) + ")");
}

}  // namespace surrogate::stages
