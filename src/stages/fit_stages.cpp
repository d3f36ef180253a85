#include "stages/fit_stages.h"

#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <condition_variable>
#include <deque>
#include <functional>
#include <future>
#include <mutex>
#include <numeric>

#include "capture/capture.h"
#include "core/digest.h"
#include "core/error.h"
#include "core/parallel.h"
#include "core/text.h"
#include "fit/fit.h"
#include "fit/render.h"
#include "hrti/light_checks.h"
#include "image/decode.h"
#include "pipeline/context.h"
#include "stages/inputs.h"
#include "stages/light_stages.h"
#include "stages/outputs.h"
#include "stages/recorded_checks.h"

namespace surrogate::stages {

using Lights = std::vector<std::array<double, 3>>;

std::string modelKey(const std::string& basis) { return "model:" + basis; }

std::string defaultFitOutput(const std::string& basisText) {
  const fit::Basis basis = fit::parseBasis(basisText);
  const bool ptm = basis == fit::Basis::PtmLrgb || basis == fit::Basis::PtmRgb;
  return std::string(capture::kFinishedDir) + "/" + fit::basisName(basis) + (ptm ? ".ptm" : ".rti");
}

namespace {
constexpr const char* kOutputParameter = "output";
constexpr const char* kModelParameter = "model";

// The previews DerivedMaps renders: a raking light from the upper left (elevation 20 deg,
// azimuth 135 deg), from the top, and a specular-enhanced view, as photographers look at RTI
// first.
struct Preview {
  const char* name;
  double elevationDeg, azimuthDeg;
  bool specular;
};
constexpr Preview kPreviews[] = {{"preview-raking.png", 20, 135, false},
                                 {"preview-top.png", 70, 90, false},
                                 {"preview-specular.png", 45, 135, true}};
constexpr const char* kNormalsFile = "normals.png";
constexpr const char* kAlbedoFile = "albedo.png";

std::string finished(const std::string& name) { return std::string(capture::kFinishedDir) + "/" + name; }

// PNG files written on threads of their own while the next picture is computed: computing a
// map already uses every core, but libdeflate compresses one file on one core, and encoding is
// most of the stage's time (the 16-bit normals of 3000x2000 take about 0.5 s). As many files are
// encoded at once as there are threads, each on its own thread; the next picture is computed as
// soon as any of them is done (waiting for the oldest, the normals, had left a core idle while
// the smaller files behind it were long written). Each file's bytes come from its pixels alone,
// and the carrier records them on the caller's thread in the order given, so the files and the
// carrier are the same at any thread count. Memory holds the pictures being encoded plus the one
// being computed: three of the five with two threads (a written picture is let go of at once,
// though its record waits for the writes before it). With one thread, each is written before
// the next is computed.
class OverlappedPngWrites {
 public:
  explicit OverlappedPngWrites(const pipeline::Context& ctx)
      : ctx_(ctx), maxPending_(effectiveThreads(ctx.settings.threads) > 1 ? effectiveThreads(ctx.settings.threads) : 0) {}
  OverlappedPngWrites(const OverlappedPngWrites&) = delete;
  OverlappedPngWrites& operator=(const OverlappedPngWrites&) = delete;
  ~OverlappedPngWrites() {
    for (Pending& p : pending_)
      if (p.write.valid()) p.write.wait();  // an error is already on its way out; let the writes end
  }

  // Writes `image` as the file `relativePath` (writePicture), then calls `record` (on this
  // thread, after the previous records).
  void add(Image image, std::string relativePath, std::function<void()> record) {
    if (maxPending_ == 0) {
      writePicture(ctx_, image, relativePath);
      record();
      return;
    }
    {
      std::unique_lock<std::mutex> lock(mutex_);
      ended_.wait(lock, [&] { return writing_ < maxPending_; });
      ++writing_;
    }
    pending_.push_back({std::async(std::launch::async,
                                   [this, image = std::move(image), path = std::move(relativePath)]() mutable {
                                     // Counted out however the write ends, so that add() never
                                     // waits for a write that has failed.
                                     struct Ended {
                                       OverlappedPngWrites& writes;
                                       ~Ended() {
                                         std::lock_guard<std::mutex> lock(writes.mutex_);
                                         --writes.writing_;
                                         writes.ended_.notify_all();
                                       }
                                     } ended{*this};
                                     // The pixels let go of as soon as they are written: the task
                                     // itself lives until its record is made, after the writes
                                     // before it (at 60 x 24 Mpx, each picture is 144 MB).
                                     const Image written = std::move(image);
                                     writePicture(ctx_, written, path);
                                   }),
                        std::move(record)});
    // Records what is written, in order, up to the first write still running.
    while (!pending_.empty() &&
           pending_.front().write.wait_for(std::chrono::seconds(0)) == std::future_status::ready)
      finishOldest();
  }

  // Waits for every pending write (rethrowing the first error) and records them in order.
  void finish() {
    while (!pending_.empty()) finishOldest();
  }

 private:
  struct Pending {
    std::future<void> write;
    std::function<void()> record;
  };

  void finishOldest() {
    Pending p = std::move(pending_.front());
    pending_.pop_front();
    p.write.get();
    p.record();
  }

  const pipeline::Context& ctx_;
  int maxPending_;  // files encoded at once; 0: write each file at once, on the caller's thread
  std::deque<Pending> pending_;
  std::mutex mutex_;
  std::condition_variable ended_;  // a write has ended
  int writing_ = 0;                // writes running, under mutex_
};

// Writes `model` to `path` (writeFile: formats::writePtm or writeRti) and takes the file's
// digests, while `written` (RunSettings::ptmWritten or hshWritten, when set) gets the model on
// a thread of its own: once the fit is done each is one core's work, and the file alone took
// 0.14 s of one core at 36 x 3000x2000 while the other waited (the report's copy of the model).
// With one thread, one after the other. Both have ended when this returns or throws.
template <class Model>
FileDigests writeModel(const std::filesystem::path& path, const Model& model,
                       void (*writeFile)(const std::filesystem::path&, const Model&),
                       const std::function<void(const std::string&, const Model&)>& written,
                       const std::string& output, int threads) {
  const auto alongside = [&] {
    if (written) written(output, model);
  };
  const auto write = [&] {
    writeFile(path, model);
    return digestFile(path);
  };
  if (effectiveThreads(threads) < 2) {
    FileDigests d = write();
    alongside();
    return d;
  }
  std::future<void> other = std::async(std::launch::async, alongside);
  FileDigests d;
  try {
    d = write();
  } catch (...) {
    other.wait();
    throw;
  }
  other.get();
  return d;
}
}  // namespace

pipeline::Parameters RtiFitOptions::toParameters() const {
  pipeline::Parameters p = fit.toParameters();
  if (!output.empty()) p.emplace_back(kOutputParameter, output);
  return p;
}

RtiFitOptions RtiFitOptions::fromParameters(const pipeline::Parameters& parameters) {
  RtiFitOptions o;
  pipeline::Parameters fitParameters;
  for (const auto& [name, value] : parameters) {
    if (name == kOutputParameter) o.output = checkedOutputPath(value);
    else fitParameters.emplace_back(name, value);
  }
  o.fit = fit::FitOptions::fromParameters(fitParameters);
  return o;
}

RtiFitOptions RtiFitOptions::forBasis(const std::string& basis) {
  RtiFitOptions o;
  o.fit.basis = fit::parseBasis(basis);
  o.output = defaultFitOutput(basis);
  return o;
}

pipeline::StageInfo RtiFitStage::info() {
  pipeline::StageInfo info = pipeline::withOptions<RtiFitOptions>(
      // Version 2: coefficients are quantised from their values rounded to float (src/fit/fit.h),
      // which moves a few bytes by one level. Version 3: a fit is conditioned on its light set
      // (src/fit/conditioning.h): where the lights leave terms too alike for 8-bit planes (a
      // narrow cone around the view axis), HSH order 3's order-3 terms and PTM's quadratic
      // terms are damped toward the lower order, so those models change; lights spread over the
      // hemisphere give version 2's bytes. Each fit also records the check residual-outlier
      // (hrti/light_checks.h), and an image the model misses far more than the others stops
      // the run unless the check is accepted. Version 4: every fit records the light matrix's
      // condition and the quantisation noise gain (how well the lights support the basis).
      {kComponent, "4", "Least-squares fit of a per-pixel reflectance model over the light directions",
       pipeline::PlanSlot::EachModel});
  info.forModel = [](const std::string& basis) { return RtiFitOptions::forBasis(basis).toParameters(); };
  info.outputs = [](const carrier::Step& step) {
    const RtiFitOptions o = RtiFitOptions::fromParameters(parametersOf(step));
    return std::vector<std::string>{o.output.empty() ? defaultFitOutput(fit::basisName(o.fit.basis)) : o.output};
  };
  info.reads = pipeline::alwaysReads({kRgbStack, kLights, kInputImages});
  return info;
}

void RtiFitStage::run(const carrier::Step& step, pipeline::Context& ctx, carrier::Result& result) {
  const auto rgb = ctx.get<ImageStack>(kRgbStack);
  const auto lights = ctx.get<Lights>(kLights);
  const auto inputs = ctx.get<InputImages>(kInputImages);
  const RtiFitOptions recorded = RtiFitOptions::fromParameters(parametersOf(step));
  fit::FitOptions options = recorded.fit;
  options.threads = ctx.settings.threads;
  options.memoryBudgetBytes = ctx.settings.fitBudget();
  const std::string basis = fit::basisName(options.basis);
  const std::string label = "Fitting " + basis;
  options.progress = [&](double f) { ctx.progress(label, f); };
  ctx.progress(label, 0);  // the fit reports once per band of rows: show the bar from the start
  const std::string output = recorded.output.empty() ? defaultFitOutput(basis) : recorded.output;

  fit::FitStatistics stats;
  std::shared_ptr<fit::Relightable> model;
  std::string format;
  FileDigests digests;
  const std::filesystem::path path = ctx.outputPath(output);
  if (options.basis == fit::Basis::PtmLrgb || options.basis == fit::Basis::PtmRgb) {
    formats::PtmFile ptm = fit::fitPtm(*rgb, *lights, options, &stats);
    digests = writeModel(path, ptm, formats::writePtm, ctx.settings.ptmWritten, output, ctx.settings.threads);
    format = formats::formatName(ptm.format);
    model = fit::makeRelightable(std::move(ptm));
  } else {
    formats::HshFile hsh = fit::fitHsh(*rgb, *lights, options, &stats);
    digests = writeModel(path, hsh, formats::writeRti, ctx.settings.hshWritten, output, ctx.settings.threads);
    format = "RTI_HSH";
    model = fit::makeRelightable(std::move(hsh));
  }
  recordOutput(ctx, step, result, output, digests, "result", format, basis,
               output.size() > 4 && output.substr(output.size() - 4) == ".ptm" ? "application/x-ptm"
                                                                             : "application/x-rti");

  result.add("value").set("name", "rmse").set("value", formatNumber(stats.rmse)).set("unit", "8-bit levels");
  result.add("value").set("name", "psnr").set("value", formatNumber(stats.psnr)).set("unit", "dB");
  result.add("value").set("name", "lightMatrixRank").set("value", std::to_string(stats.rank));
  for (std::size_t n = 0; n < inputs->size() && n < stats.perImageRmse.size(); ++n) {
    result.add("imageValue").set("image", (*inputs)[n].fileId).set("name", "rmse")
        .set("value", formatNumber(stats.perImageRmse[n])).set("unit", "8-bit levels");
  }
  // The images the model fits worst: where a moved object, a missed flash or a wrong light
  // direction shows first.
  std::vector<std::size_t> order(stats.perImageRmse.size());
  std::iota(order.begin(), order.end(), 0);
  std::stable_sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) {
    return stats.perImageRmse[a] > stats.perImageRmse[b];
  });
  std::string worst;
  for (std::size_t k = 0; k < std::min<std::size_t>(3, order.size()); ++k) {
    worst += (worst.empty() ? "" : ", ") + (*inputs)[order[k]].stem + " (" +
             fixedDecimals(stats.perImageRmse[order[k]], 2) + ")";
  }
  ctx.carrier.addLog("info", step.id, basis + " fit: RMSE " + fixedDecimals(stats.rmse, 3) + ", PSNR " +
                                          fixedDecimals(stats.psnr, 2) + " dB; worst images: " + worst);
  // An image the model misses far more than the others (hrti/light_checks.h, residual-outlier).
  std::vector<std::string> names;
  for (const InputImage& in : *inputs) names.push_back(in.stem);
  recordChecks(step, ctx, result, {hrti::residualCheck(stats.perImageRmse, names)},
               {"fit checks", "the fit", "its result cannot be trusted"},
               [&](const hrti::LightCheck& c) { return excludeImagesFix(c, names); });
  // How well the lights support this basis, whatever was done about it (docs/hrti-math.md,
  // "The default bases and the light coverage"); the damping, only when it changed the fit.
  result.add("value").set("name", "lightMatrixCondition").set("value", formatNumber(stats.conditionNumber));
  result.add("value").set("name", "quantisationNoiseGain").set("value", formatNumber(stats.noiseGain));
  if (stats.regularisation > 0) {
    std::string damped;
    for (int k : stats.dampedTerms) damped += (damped.empty() ? "" : " ") + std::to_string(k);
    result.add("value").set("name", "regularisation").set("value", formatNumber(stats.regularisation));
    result.add("value").set("name", "dampedTerms").set("value", damped);
    result.add("value").set("name", "plainQuantisationNoiseGain").set("value", formatNumber(stats.plainNoiseGain));
    ctx.carrier.addLog("warning", step.id,
                       fit::conditioningWarning(options.basis, static_cast<int>(lights->size()), stats));
  }
  if (stats.rank < fit::basisTerms(options.basis))
    ctx.carrier.addLog("warning", step.id, "the light directions do not determine all " +
                                               std::to_string(fit::basisTerms(options.basis)) +
                                               " terms of " + basis + " (rank " + std::to_string(stats.rank) +
                                               "): add lights at other elevations and azimuths");
  ctx.put(modelKey(basis), model);
}

pipeline::Parameters DerivedMapsOptions::toParameters() const { return {{kModelParameter, model}}; }

DerivedMapsOptions DerivedMapsOptions::fromParameters(const pipeline::Parameters& parameters) {
  DerivedMapsOptions o;
  for (const auto& [name, value] : parameters) {
    if (name != kModelParameter)
      throw Error(ErrorKind::Input, name + "=" + value, "derived maps",
                  "is not a parameter of DerivedMaps (model)");
    try {
      fit::parseBasis(value);
    } catch (const Error&) {
      throw Error(ErrorKind::Input, name + "=" + value, "derived maps",
                  "is not a model Surrogate fits (ptm-lrgb, ptm-rgb, hsh2, hsh3)");
    }
    o.model = value;  // as recorded: the key RtiFit put the model under (modelKey)
  }
  return o;
}

pipeline::StageInfo DerivedMapsStage::info() {
  pipeline::StageInfo info = pipeline::withOptions<DerivedMapsOptions>(
      // Version 2: the Lambertian fit of normals and albedo multiplies the coefficients by the
      // fit matrix composed with the basis (src/fit/lambert.h), a different rounding that can
      // move a sample by one level; its PNG files are encoded with fixed Up filters and
      // run-length deflate (src/image/png_encoder.h). Version 3: those PNG files compressed by
      // libdeflate at level 1 (src/image/png_encoder.h).
      {kComponent, "3", "Surface normals, albedo and relit previews from a model",
       pipeline::PlanSlot::AfterModels});
  info.forModel = [](const std::string& basis) {
    DerivedMapsOptions o;
    o.model = fit::basisName(fit::parseBasis(basis));
    return o.toParameters();
  };
  info.outputs = [](const carrier::Step&) {
    std::vector<std::string> out = {finished(kNormalsFile), finished(kAlbedoFile)};
    for (const Preview& p : kPreviews) out.push_back(finished(p.name));
    return out;
  };
  info.reads = [](const carrier::Step& step) {
    return std::vector<std::string>{modelKey(DerivedMapsOptions::fromParameters(parametersOf(step)).model)};
  };
  return info;
}

void DerivedMapsStage::run(const carrier::Step& step, pipeline::Context& ctx, carrier::Result& result) {
  const std::string basis = DerivedMapsOptions::fromParameters(parametersOf(step)).model;
  const auto model = ctx.get<fit::Relightable>(modelKey(basis));
  // Five pictures of about equal cost (normals, albedo, three previews): the bar moves by one
  // fifth as each is written.
  int pictures = 0;
  const auto written = [&ctx, &pictures] { ctx.progress("Normals, albedo and previews", pictures++ / 5.0); };
  written();
  OverlappedPngWrites writes(ctx);
  const auto record = [&](const std::string& name, const char* kind) {
    recordOutput(ctx, step, result, finished(name), "result", "PNG", kind, "image/png");
    written();
  };

  int fallback = 0;
  writes.add(model->normalMap(&fallback, ctx.settings.threads), finished(kNormalsFile), [&] {
    record(kNormalsFile, "normals");
    result.add("value").set("name", "normalFallbackPixels").set("value", std::to_string(fallback));
    const double fraction = double(fallback) / (double(model->width()) * model->height());
    ctx.carrier.addLog(fraction > 0.05 ? "warning" : "info", step.id,
                       std::to_string(fallback) + " pixels (" + fixedDecimals(100 * fraction, 2) +
                           " %) had no valid PTM maximum and took the least-squares Lambertian normal");
  });
  writes.add(model->albedoMap(ctx.settings.threads), finished(kAlbedoFile),
             [&] { record(kAlbedoFile, "albedo"); });
  for (const Preview& p : kPreviews) {
    const double e = p.elevationDeg * M_PI / 180, a = p.azimuthDeg * M_PI / 180;
    fit::RenderOptions options;
    options.specular = p.specular && basis.rfind("ptm", 0) == 0;
    options.threads = ctx.settings.threads;
    const std::array<double, 3> light{std::cos(e) * std::cos(a), std::cos(e) * std::sin(a), std::sin(e)};
    writes.add(model->render(light, options), finished(p.name), [&record, &p] { record(p.name, "preview"); });
  }
  writes.finish();
}

}  // namespace surrogate::stages
