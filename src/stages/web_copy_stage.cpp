#include "stages/web_copy_stage.h"

#include <filesystem>

#include "capture/capture.h"
#include "core/atomic_file.h"
#include "core/error.h"
#include "fit/basis.h"
#include "fit/learned.h"
#include "pipeline/context.h"
#include "publish/web_layout.h"
#include "stages/rti_fit_stage.h"
#include "stages/outputs.h"
#include "stages/recorded_numbers.h"

namespace surrogate::stages {

namespace fs = std::filesystem;

namespace {
constexpr const char* kStep = "web copy";


// What a file of the layout is, for the carrier: format, media type and the output's kind.
struct FileKind {
  const char* format;
  const char* mediaType;
  const char* kind;
};

FileKind kindOf(const std::string& name) {
  const std::string ext = fs::path(name).extension().string();
  if (name == "info.json") return {"JSON", "application/json", "web-info"};
  if (ext == ".jpg") return {"JPEG", "image/jpeg", name.find('/') == std::string::npos ? "web-plane" : "web-tile"};
  if (ext == ".dzi") return {"DZI", "application/xml", "web-tiles"};
  if (ext == ".html") return {"HTML", "text/html", "web-viewer"};
  if (ext == ".js") return {"JavaScript", "text/javascript", "web-viewer"};
  return {"other", "application/octet-stream", "web"};
}

// The model file the RtiFit step of `basis` wrote (its recorded output, or the default).
std::string fittedModelPath(const carrier::Carrier& c, const std::string& basis) {
  for (const carrier::Step& s : c.process) {
    if (s.component != RtiFitStage::kComponent) continue;
    const RtiFitOptions o = RtiFitOptions::fromParameters(parametersOf(s));
    if (fit::basisName(o.fit.basis) == basis) return o.output.empty() ? defaultFitOutput(basis) : o.output;
  }
  throw Error(ErrorKind::Input, basis, kStep,
              "no RtiFit step of the process list fits this model; a web copy follows the fit of its model");
}
}  // namespace

std::string webCopyFolder(const std::string& basis) {
  return std::string(capture::kFinishedDir) + "/web/" + basis;
}

std::string webIndexPath() { return std::string(capture::kFinishedDir) + "/web/index.html"; }

pipeline::Parameters WebCopyOptions::toParameters() const {
  return {{"model", model},
          {"quality", std::to_string(quality)},
          {"tiles", tiles},
          {"tileSize", std::to_string(tileSize)}};
}

WebCopyOptions WebCopyOptions::fromParameters(const pipeline::Parameters& parameters) {
  WebCopyOptions o;
  for (const auto& [name, value] : parameters) {
    if (name == "model") {
      try {
        fit::parseBasis(value);
      } catch (const Error&) {
        throw badParameter(kStep, name, value, "is not a model Surrogate fits (ptm-lrgb, ptm-rgb, hsh2, hsh3)");
      }
      o.model = value;
    } else if (name == "quality") {
      o.quality = recordedInteger(kStep, name, value, 1, 100);
    } else if (name == "tiles") {
      if (value != "auto" && value != "none" && value != "deepzoom")
        throw badParameter(kStep, name, value, "is not a tile layout (auto, none, deepzoom)");
      o.tiles = value;
    } else if (name == "tileSize") {
      o.tileSize = recordedInteger(kStep, name, value, 16, 4096);
    } else {
      throw badParameter(kStep, name, value, "is not a parameter of WebCopy (model, quality, tiles, tileSize)");
    }
  }
  return o;
}

pipeline::StageInfo WebCopyStage::info() {
  // Version 1: the layout of publish/web_layout.h (docs/formats.md, "The web layout").
  // Version 2: the normals and albedo in viewer-data.js come from the Lambertian fit composed
  //            with the basis (src/fit/lambert.h), a different rounding that can move a sample.
  // Version 3: each file's PRONOM identifier is recorded (formats/pronom.h: the planes, with
  //            libjpeg's Adobe marker and no JFIF one, are a raw JPEG stream, fmt/41; the viewer
  //            HTML 5, fmt/471); the files are the same.
  // Version 4: index.html shows the carrier's title, creators, rights and licence and the
  //            basis, and zooms and pans; the last WebCopy step of the process list also writes
  //            finished-files/web/index.html, linking every model's folder.
  pipeline::StageInfo info = pipeline::withOptions<WebCopyOptions>(
      {kComponent, "4", "Web copy of a model: info.json, JPEG coefficient planes and a viewer",
       pipeline::PlanSlot::Publish});
  info.forModel = [](const std::string& basis) {
    return pipeline::Parameters{{"model", fit::basisName(fit::parseBasis(basis))}};
  };
  // A learned basis (rbf, bln) is written as its web layout by LearnedFit itself
  // (finished-files/<basis>/): no copy of it is made.
  info.takesModel = [](const std::string& basis) { return !fit::isLearnedBasisName(basis); };
  // Any WebCopy step may be the last of its process list, which writes the index.
  info.outputs = [](const carrier::Step& step) {
    return std::vector<std::string>{webCopyFolder(WebCopyOptions::fromParameters(parametersOf(step)).model) + "/*",
                                    webIndexPath()};
  };
  info.reads = pipeline::alwaysReads({});  // the model's file, not the fit's object
  return info;
}

void WebCopyStage::run(const carrier::Step& step, pipeline::Context& ctx, carrier::Result& result) {
  const WebCopyOptions o = WebCopyOptions::fromParameters(parametersOf(step));
  const std::string label = "Web copy of " + o.model;
  ctx.progress(label, 0);
  const std::string model = fittedModelPath(ctx.carrier, o.model);
  const carrier::FileRecord* input = ctx.carrier.findFileByPath(model);
  if (!input)
    throw Error(ErrorKind::Input, model, kStep, "is not recorded: the fit of " + o.model + " did not run before");
  result.add("input").set("file", input->id).set("kind", o.model);

  publish::PublishOptions options;
  options.description = publish::webDescriptionOf(ctx.carrier);
  options.quality = o.quality;
  options.tiles = publish::parseTileLayout(o.tiles);
  options.tileSize = o.tileSize;
  options.threads = ctx.settings.threads;
  options.memoryBudget = ctx.settings.memoryBudget;
  const publish::WebLayoutFiles layout = publish::webLayoutOfFile(ctx.outputPath(model), options);
  ctx.progress(label, 0.5);

  const std::string folder = webCopyFolder(o.model);
  for (const auto& [name, bytes] : layout.files) {
    const std::string relative = checkedOutputPath(folder + "/" + name);
    const fs::path file = ctx.outputPath(relative);
    fs::create_directories(file.parent_path());
    writeFileAtomically(file, bytes);
    const FileKind k = kindOf(name);
    recordOutput(ctx, step, result, relative, "result", k.format, k.kind, k.mediaType);
  }
  // The index of every model the process list publishes, written once, by the last WebCopy step
  // (the models' folders are the steps' own, so the index is known before they are written).
  std::vector<publish::IndexedModel> models;
  const carrier::Step* last = nullptr;
  for (const carrier::Step& s : ctx.carrier.process) {
    if (s.component != kComponent) continue;
    const std::string basis = WebCopyOptions::fromParameters(parametersOf(s)).model;
    models.push_back({basis, basis});
    last = &s;
  }
  if (last && last->id == step.id) {
    const std::string relative = checkedOutputPath(webIndexPath());
    writeFileAtomically(ctx.outputPath(relative), publish::webIndexHtml(options.description, models));
    recordOutput(ctx, step, result, relative, "result", "HTML", "web-index", "text/html");
  }
  ctx.carrier.addLog("info", step.id,
                     "web copy of " + model + " in " + folder + "/: " + std::to_string(layout.files.size()) +
                         " files, JPEG quality " + std::to_string(o.quality) +
                         (layout.model.tiles.empty() ? ", whole planes"
                                                     : ", Deep Zoom tiles of " + std::to_string(o.tileSize) + " texels"));
}

}  // namespace surrogate::stages
