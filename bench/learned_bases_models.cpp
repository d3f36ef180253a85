// The models of the learned-bases benchmark (learned_bases_models.h), each relit from what a
// viewer gets wherever there is such an artefact.
#include "learned_bases_models.h"

#include <chrono>
#include <memory>
#include <system_error>

#include "fit/fit.h"
#include "fit/held_out.h"
#include "fit/learned.h"
#include "fit/render.h"
#include "formats/ptm.h"
#include "formats/rti_hsh.h"
#include "publish/learned_layout.h"
#include "publish/web_layout.h"
#include "publish/web_reader.h"

namespace fs = std::filesystem;

namespace surrogate::bench {
namespace {

double secondsSince(std::chrono::steady_clock::time_point start) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

// A fresh empty folder under `scratch` for one layout (writeWebLayoutFolder wants none there).
fs::path freshFolder(const fs::path& scratch, const std::string& name) {
  fs::path folder = scratch / name;
  std::error_code ignored;
  fs::remove_all(folder, ignored);
  fs::create_directories(scratch);
  return folder;
}

// The relight function of a layout read back: learned, PTM or HSH.
std::function<Image(const Light&)> relightOf(publish::WebLayoutModel web, int threads) {
  auto held = std::make_shared<publish::WebLayoutModel>(std::move(web));
  fit::RenderOptions options;
  options.threads = threads;
  if (held->isLearned)
    return [held, threads](const Light& l) { return fit::renderLearned(held->learned, l, threads); };
  if (held->isPtm) return [held, options](const Light& l) { return fit::render(held->ptm, l, options); };
  return [held, options](const Light& l) { return fit::render(held->hsh, l, options); };
}

}  // namespace

std::uint64_t layoutBytes(const fs::path& folder) {
  std::uint64_t bytes = 0;
  for (const auto& entry : fs::directory_iterator(folder)) {
    const std::string name = entry.path().filename().string();
    if (entry.is_regular_file() && (name == "info.json" || name.rfind("plane_", 0) == 0))
      bytes += entry.file_size();
  }
  return bytes;
}

Evaluated evaluateSurrogate(const Fold& fold, fit::Basis basis, bool web, int quality, int threads) {
  fit::FitOptions options;
  options.basis = basis;
  options.threads = threads;
  const bool ptm = basis == fit::Basis::PtmLrgb || basis == fit::Basis::PtmRgb;
  const auto start = std::chrono::steady_clock::now();
  auto ptmModel = std::make_shared<formats::PtmFile>();
  auto hshModel = std::make_shared<formats::HshFile>();
  if (ptm) *ptmModel = fit::fitPtm(*fold.fit, fold.fitLights, options);
  else *hshModel = fit::fitHsh(*fold.fit, fold.fitLights, options);
  Evaluated e;
  e.seconds = secondsSince(start);
  e.name = std::string(fit::basisName(basis)) + (ptm ? " .ptm" : " .rti");
  fit::RenderOptions render;
  render.threads = threads;
  if (!web) {
    e.bytes = ptm ? formats::serializePtm(*ptmModel).size() : formats::serializeRti(*hshModel).size();
    if (ptm) e.relight = [ptmModel, render](const Light& l) { return fit::render(*ptmModel, l, render); };
    else e.relight = [hshModel, render](const Light& l) { return fit::render(*hshModel, l, render); };
    return e;
  }
  publish::PublishOptions publishOptions;
  publishOptions.quality = quality;
  publishOptions.tiles = publish::TileLayout::None;
  publishOptions.threads = threads;
  const fs::path folder = freshFolder(fs::temp_directory_path() / "learned_bases", e.name + "-web");
  publish::writeWebLayoutFolder(ptm ? publish::webLayoutOf(*ptmModel, publishOptions)
                                    : publish::webLayoutOf(*hshModel, publishOptions),
                                folder);
  e.name = std::string(fit::basisName(basis)) + " web q" + std::to_string(quality);
  e.bytes = layoutBytes(folder);
  e.relight = relightOf(publish::readWebLayout(folder), threads);
  return e;
}

Evaluated evaluateLearned(const Fold& fold, const fit::LearnedOptions& options, int quality, int lastQuality,
                          const fs::path& scratch) {
  const auto start = std::chrono::steady_clock::now();
  fit::LearnedModel model = fit::fitLearned(*fold.fit, fold.fitLights, options);
  Evaluated e;
  e.seconds = secondsSince(start);
  e.name = std::string(fit::learnedKindName(options.kind)) + " " + std::to_string(options.planes) +
           (options.kind == fit::LearnedKind::Bilinear ? " R" + std::to_string(options.resolution) : "") +
           " q" + std::to_string(quality) + (lastQuality != quality ? "-" + std::to_string(lastQuality) : "");
  publish::PublishOptions publishOptions;
  publishOptions.quality = quality;
  publishOptions.lastQuality = lastQuality;
  publishOptions.tiles = publish::TileLayout::None;
  const fs::path folder = freshFolder(scratch, "learned");
  publish::writeWebLayoutFolder(publish::webLayoutOf(model, publishOptions), folder);
  e.bytes = layoutBytes(folder);
  e.relight = relightOf(publish::readWebLayout(folder), options.threads);
  return e;
}

Evaluated evaluateLayout(const fs::path& folder, int threads) {
  Evaluated e;
  e.name = "layout " + folder.string();
  e.bytes = layoutBytes(folder);
  e.relight = relightOf(publish::readWebLayout(folder), threads);
  return e;
}

Evaluated evaluateNearest(const Fold& fold, int count) {
  Evaluated e;
  e.name = std::to_string(count) + " nearest photographs";
  const Fold* f = &fold;
  e.relight = [f, count](const Light& l) { return fit::nearestPhotographBlend(*f->fit, f->fitLights, l, count); };
  return e;
}

}  // namespace surrogate::bench
