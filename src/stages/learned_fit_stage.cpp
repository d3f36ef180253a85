#include "stages/learned_fit_stage.h"

#include <filesystem>

#include "capture/capture.h"
#include "core/error.h"
#include "core/text.h"
#include "fit/learned_relightable.h"
#include "pipeline/context.h"
#include "publish/learned_layout.h"
#include "stages/held_out_quality.h"
#include "stages/held_out_record.h"
#include "stages/inputs.h"
#include "stages/outputs.h"
#include "stages/recorded_numbers.h"
#include "stages/rti_fit_stage.h"

namespace surrogate::stages {

namespace fs = std::filesystem;
using Lights = std::vector<std::array<double, 3>>;

namespace {
constexpr const char* kStep = "learned fit";


// The planes' JPEG qualities as the viewer reads them: whole planes (no Deep Zoom tiles), from
// `quality` on the first to `lastQuality` on the last.
publish::PublishOptions webOptions(const LearnedFitOptions& o) {
  publish::PublishOptions web;
  web.quality = o.quality;
  web.lastQuality = o.lastQuality;
  web.tiles = publish::TileLayout::None;
  return web;
}
}  // namespace

std::string learnedFolder(const std::string& basis) { return std::string(capture::kFinishedDir) + "/" + basis; }

pipeline::Parameters LearnedFitOptions::toParameters() const {
  return {{"basis", basis},
          {"planes", std::to_string(planes)},
          {"resolution", std::to_string(resolution)},
          {"quality", std::to_string(quality) + (lastQuality != quality ? ":" + std::to_string(lastQuality) : "")},
          {"holdout", std::to_string(holdout)}};
}

LearnedFitOptions LearnedFitOptions::fromParameters(const pipeline::Parameters& parameters) {
  LearnedFitOptions o;
  for (const auto& [name, value] : parameters) {
    if (name == "basis") {
      if (!fit::isLearnedBasisName(value)) throw badParameter(kStep, name, value, "is not a learned basis (rbf, bln)");
      o.basis = value;
    } else if (name == "planes") {
      o.planes = recordedInteger(kStep, name, value, 3, 120);
      if (o.planes % 3) throw badParameter(kStep, name, value, "needs a multiple of 3 (a JPEG plane holds three)");
    } else if (name == "resolution") {
      o.resolution = recordedInteger(kStep, name, value, 4, 32);
    } else if (name == "quality") {
      const std::size_t colon = value.find(':');
      o.quality = recordedInteger(kStep, name, value.substr(0, colon), 1, 100);
      o.lastQuality = colon == std::string::npos ? o.quality : recordedInteger(kStep, name, value.substr(colon + 1), 1, 100);
    } else if (name == "holdout") {
      o.holdout = recordedInteger(kStep, name, value, 0, 1000);
    } else {
      throw badParameter(kStep, name, value,
                         "is not a parameter of LearnedFit (basis, planes, resolution, quality, holdout)");
    }
  }
  return o;
}

fit::LearnedOptions LearnedFitOptions::fitOptions() const {
  fit::LearnedOptions f;
  f.kind = fit::parseLearnedKind(basis);
  f.planes = planes;
  f.resolution = resolution;
  return f;
}

pipeline::StageInfo LearnedFitStage::info() {
  // Version 1: fit/learned.h's fit (kernel ridge regression chosen by leave-one-out, node
  // values fitted through the viewer's interpolation, principal components), written as
  // publish/learned_layout.h's web layout.
  pipeline::StageInfo info = pipeline::withOptions<LearnedFitOptions>(
      {kComponent, "1", "Learned basis (RBF or bilinear) fitted to the photographs, written as a web layout",
       pipeline::PlanSlot::EachModel});
  info.takesModel = [](const std::string& basis) { return fit::isLearnedBasisName(basis); };
  info.forModel = [](const std::string& basis) { return pipeline::Parameters{{"basis", basis}}; };
  info.outputs = [](const carrier::Step& step) {
    return std::vector<std::string>{learnedFolder(LearnedFitOptions::fromParameters(parametersOf(step)).basis) + "/*"};
  };
  info.reads = pipeline::alwaysReads({kRgbStack, kLights, kInputImages});
  return info;
}


void LearnedFitStage::run(const carrier::Step& step, pipeline::Context& ctx, carrier::Result& result) {
  const auto rgb = ctx.get<ImageStack>(kRgbStack);
  const auto lights = ctx.get<Lights>(kLights);
  const LearnedFitOptions o = LearnedFitOptions::fromParameters(parametersOf(step));
  const std::string label = "Fitting " + o.basis;
  fit::LearnedOptions options = o.fitOptions();
  options.threads = ctx.settings.threads;
  options.progress = [&](double f) { ctx.progress(label, f); };
  ctx.progress(label, 0);
  fit::LearnedStatistics stats;
  const fit::LearnedModel model = fit::fitLearned(*rgb, *lights, options, &stats);

  // The folder whole or not at all (a hidden partial folder renamed into place); a folder left
  // by an earlier write of this step into the same output root is this step's own.
  const std::string folder = checkedOutputPath(learnedFolder(o.basis));
  const publish::PublishOptions web = webOptions(o);
  const publish::WebLayoutFiles layout = publish::webLayoutOf(model, web);
  std::error_code ec;
  fs::remove_all(ctx.outputPath(folder), ec);
  publish::writeWebLayoutFolder(layout, ctx.outputPath(folder));
  for (const auto& [name, bytes] : layout.files) {
    const std::string relative = checkedOutputPath(folder + "/" + name);
    if (name == "info.json") recordOutput(ctx, step, result, relative, "result", "JSON", "learned-model", "application/json");
    else recordOutput(ctx, step, result, relative, "result", "JPEG", "learned-plane", "image/jpeg");
  }

  // The planes the photographs hold (fit::learnedPlanesFor): fewer than asked for a small capture.
  result.add("value").set("name", "planesFitted").set("value", std::to_string(model.planes));
  result.add("value").set("name", "kernelWidth").set("value", formatNumber(model.kernelWidth)).set("unit", "radians");
  result.add("value").set("name", "ridge").set("value", formatNumber(model.ridge));
  result.add("value").set("name", "psnr").set("value", formatNumber(stats.psnr)).set("unit", "dB");
  result.add("value").set("name", "leaveOneOutPsnr").set("value", formatNumber(stats.leaveOneOutPsnr)).set("unit", "dB");
  result.add("value").set("name", "explainedVariance").set("value", formatNumber(stats.explainedVariance));
  result.add("value").set("name", "sampledTexels").set("value", std::to_string(stats.sampledTexels));
  ctx.carrier.addLog("info", step.id,
                     o.basis + " fit: " + std::to_string(model.planes) + " planes" +
                         (model.planes < o.planes ? " (the " + std::to_string(lights->size()) + " photographs hold no more; " +
                                                        std::to_string(o.planes) + " asked)" : std::string()) +
                         ", PSNR " + fixedDecimals(stats.psnr, 2) +
                         " dB at the captured lights, " + fixedDecimals(stats.leaveOneOutPsnr, 2) +
                         " dB leaving each photograph out; " + std::to_string(layout.files.size()) + " files in " +
                         folder + "/ (JPEG quality " + std::to_string(o.quality) +
                         (o.lastQuality != o.quality ? " to " + std::to_string(o.lastQuality) : "") + ")");
  if (o.holdout > 0) {
    ModelRecipe recipe;
    recipe.basis = o.basis;
    recipe.learned = o.fitOptions();
    recipe.web = webOptions(o);
    recipe.threads = ctx.settings.threads;
    measureAndRecordHeldOut(step, ctx, result, recipe, *rgb, *lights, o.holdout);
  }
  // As a viewer shows it: maps, previews and the report's view see the planes' JPEG compression.
  ctx.put(modelKey(o.basis), std::shared_ptr<fit::Relightable>(fit::makeRelightable(learnedAsViewed(model, layout))));
}

}  // namespace surrogate::stages
