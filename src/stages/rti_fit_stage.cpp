#include "stages/rti_fit_stage.h"

#include "carrier/advice.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <functional>
#include <future>
#include <numeric>
#include <ostream>
#include <streambuf>

#include "capture/capture.h"
#include "core/digest.h"
#include "core/error.h"
#include "core/parallel.h"
#include "core/text.h"
#include "fit/fit.h"
#include "fit/learned.h"
#include "fit/render.h"
#include "hrti/light_checks.h"
#include "image/decode.h"
#include "pipeline/context.h"
#include "stages/held_out_record.h"
#include "stages/inputs.h"
#include "stages/outputs.h"
#include "stages/recorded_numbers.h"
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
// The last version that added the fit error's squares one pixel after the other in double
// precision: its steps still do.
constexpr const char* kSerialErrorsVersion = "7";
constexpr const char* kOutputParameter = "output";
constexpr const char* kHoldoutParameter = "holdout";

// A stream that only hashes what is written to it: the digests of a file taken from the same
// writer's output in memory (formats' writeRti / writePtm to a std::ostream), not read back.
class DigestStream : public std::streambuf {
 public:
  DigestStream() : digest_({DigestAlgorithm::Sha256}) {}
  FileDigests digests() {
    FileDigests d;
    d.size = digest_.bytes();
    d.sha256 = digest_.hex(DigestAlgorithm::Sha256);
    return d;
  }

 protected:
  std::streamsize xsputn(const char* s, std::streamsize n) override {
    digest_.update(s, static_cast<std::size_t>(n));
    return n;
  }
  int_type overflow(int_type c) override {
    if (traits_type::eq_int_type(c, traits_type::eof())) return traits_type::not_eof(c);
    const char byte = traits_type::to_char_type(c);
    digest_.update(&byte, 1);
    return c;
  }

 private:
  MultiDigest digest_;
};

// Writes `model` to `path` (writeFile: formats::writePtm or writeRti) and takes the file's
// digests from the same bytes in memory (serialise: the same writer to a std::ostream), while
// `written` (RunSettings::ptmWritten or hshWritten, when set) gets the model: once the fit is
// done each is one core's work. The file alone took 0.14 s of one core at 36 x 3000x2000 while
// the other waited (the report's copy of the model); at 36 x 1200x800 the .rti's 11.5 MB took
// 25-38 ms to write and 8 ms to sync, and reading it back to hash it 9 ms more, one core idle.
// The file's bytes are the serialised ones when writeFile returns (it throws on any short
// write), so the digests are the file's. With one thread, one after the other. All have ended
// when this returns or throws.
template <class Model>
FileDigests writeModel(const std::filesystem::path& path, const Model& model,
                       void (*writeFile)(const std::filesystem::path&, const Model&),
                       void (*serialise)(std::ostream&, const Model&, const std::string&),
                       const std::function<void(const std::string&, const Model&)>& written,
                       const std::string& output, int threads) {
  const auto alongside = [&] {
    if (written) written(output, model);
  };
  const auto hash = [&] {
    DigestStream digest;
    std::ostream out(&digest);
    serialise(out, model, path.string());
    return digest.digests();
  };
  if (effectiveThreads(threads) < 2) {
    writeFile(path, model);
    FileDigests d = hash();
    alongside();
    return d;
  }
  std::future<FileDigests> digests = std::async(std::launch::async, hash);
  std::future<void> other = std::async(std::launch::async, alongside);
  try {
    writeFile(path, model);
  } catch (...) {
    digests.wait();
    other.wait();
    throw;
  }
  // Both taken, so that neither is left running when one throws.
  std::exception_ptr failed;
  FileDigests d;
  try {
    d = digests.get();
  } catch (...) {
    failed = std::current_exception();
  }
  try {
    other.get();
  } catch (...) {
    if (!failed) failed = std::current_exception();
  }
  if (failed) std::rethrow_exception(failed);
  return d;
}
}  // namespace

pipeline::Parameters RtiFitOptions::toParameters() const {
  pipeline::Parameters p = fit.toParameters();
  if (!output.empty()) p.emplace_back(kOutputParameter, output);
  if (holdout > 0) p.emplace_back(kHoldoutParameter, std::to_string(holdout));
  return p;
}

RtiFitOptions RtiFitOptions::fromParameters(const pipeline::Parameters& parameters) {
  RtiFitOptions o;
  pipeline::Parameters fitParameters;
  for (const auto& [name, value] : parameters) {
    if (name == kOutputParameter) {
      o.output = checkedOutputPath(value);
    } else if (name == kHoldoutParameter) {
      o.holdout = recordedInteger("RtiFit", name, value, 0, 1000);
    } else {
      fitParameters.emplace_back(name, value);
    }
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
      // Version 5: a .ptm's PRONOM identifier (fmt/519) is recorded (formats/pronom.h); the
      // files are the same. Version 6: lights at known positions (LightDirections version 7,
      // value nearLights): each pixel is fitted to its own light directions and its values
      // brought to the frame centre's light by the inverse square of its distance
      // (fit/near_lights.h); lights at infinity give version 5's bytes. Version 7: parameter
      // holdout K > 0 also fits without K photographs and records the model's PSNR and SSIM at
      // their lights (stages/held_out_record.h); the files are version 6's. Version 8: the fit
      // error (rmse, psnr, each image's rmse) adds its squares in eight lanes, and with lights
      // at infinity compares in single precision (fit::ErrorMeasure, fit/error_kernels.h): the
      // far errors in a third of the time, within a few 1e-5 levels of version 7's; the files
      // are version 7's, and steps of version 7 still measure as they did (kSerialErrorsVersion).
      {kComponent, "8", "Least-squares fit of a per-pixel reflectance model over the light directions",
       pipeline::PlanSlot::EachModel});
  info.alsoRuns = {kSerialErrorsVersion};
  info.forModel = [](const std::string& basis) { return RtiFitOptions::forBasis(basis).toParameters(); };
  // The learned bases (rbf, bln) are LearnedFit's (stages/learned_fit_stage.h).
  info.takesModel = [](const std::string& basis) { return !fit::isLearnedBasisName(basis); };
  info.outputs = [](const carrier::Step& step) {
    const RtiFitOptions o = RtiFitOptions::fromParameters(parametersOf(step));
    return std::vector<std::string>{o.output.empty() ? defaultFitOutput(fit::basisName(o.fit.basis)) : o.output};
  };
  info.reads = pipeline::alwaysReads({kRgbStack, kLights, kInputImages, kLightPlaces, kStackFrame});
  return info;
}

namespace {

// The fit's near lights (fit/near_lights.h) from the lights' places (LightDirections): the
// frame coordinates of docs/hrti-math.md ("Near lights") taken to the stack's pixels, which a
// crop or a resize moved (StackFrame). Returns how many lights are near (0: the far fit).
int nearLightsOf(pipeline::Context& ctx, std::size_t lights,
                 std::vector<fit::NearLight>* out) {
  out->clear();
  if (!ctx.has(kLightPlaces) || !ctx.has(kStackFrame)) return 0;
  const auto places = ctx.get<LightPlaces>(kLightPlaces);
  if (!places->anyNear()) return 0;
  const StackFrame frame = *ctx.get<StackFrame>(kStackFrame);
  if (places->lights.size() != lights || frame.fullWidth != places->frameWidth ||
      frame.fullHeight != places->frameHeight)
    throw Error(ErrorKind::Internal, "", "RtiFit",
                "the lights' places do not match the images fitted; this is a bug in Surrogate, please report it");
  // Frame point (X, Y) of full-frame pixel (u, v): (u - cu, cv - v); the stack's pixel (x, y)
  // is the point (x, -y) of the fit's own units, u = x0 + sx x, v = y0 + sy y.
  const double cu = (frame.fullWidth - 1) / 2.0, cv = (frame.fullHeight - 1) / 2.0;
  int near = 0;
  for (const LightPlace& p : places->lights) {
    fit::NearLight l;
    if (p.near) {
      const auto& X = p.position;
      l.near = true;
      l.position = {(X[0] + cu - frame.x0) / frame.sx, (X[1] - cv + frame.y0) / frame.sy, X[2] / frame.sx};
      l.referenceDistance = std::sqrt(X[0] * X[0] + X[1] * X[1] + X[2] * X[2]) / frame.sx;
      ++near;
    }
    out->push_back(l);
  }
  return near;
}

}  // namespace

void RtiFitStage::run(const carrier::Step& step, pipeline::Context& ctx, carrier::Result& result) {
  const auto rgb = ctx.get<ImageStack>(kRgbStack);
  const auto lights = ctx.get<Lights>(kLights);
  const auto inputs = ctx.get<InputImages>(kInputImages);
  const RtiFitOptions recorded = RtiFitOptions::fromParameters(parametersOf(step));
  fit::FitOptions options = recorded.fit;
  options.threads = ctx.settings.threads;
  options.memoryBudgetBytes = ctx.settings.fitBudget();
  options.errors = step.version == kSerialErrorsVersion ? fit::ErrorMeasure::Serial : fit::ErrorMeasure::Lanes;
  const std::string basis = fit::basisName(options.basis);
  const std::string label = "Fitting " + basis;
  options.progress = [&](double f) { ctx.progress(label, f); };
  ctx.progress(label, 0);  // the fit reports once per band of rows: show the bar from the start
  const std::string output = recorded.output.empty() ? defaultFitOutput(basis) : recorded.output;
  const int nearCount = nearLightsOf(ctx, lights->size(), &options.nearLights);
  if (nearCount > 0) {
    result.add("value").set("name", "nearLights").set("value", std::to_string(nearCount))
        .set("unit", "of " + std::to_string(lights->size()) + " lights");
    ctx.carrier.addLog("info", step.id,
                       basis + " fit: " + std::to_string(nearCount) + " of the " + std::to_string(lights->size()) +
                           " lights at known positions: each pixel fitted to its own light directions, its "
                           "values brought to the frame centre's light by the inverse square of the distance");
  }

  fit::FitStatistics stats;
  std::shared_ptr<fit::Relightable> model;
  std::string format;
  FileDigests digests;
  const std::filesystem::path path = ctx.outputPath(output);
  if (options.basis == fit::Basis::PtmLrgb || options.basis == fit::Basis::PtmRgb) {
    formats::PtmFile ptm = fit::fitPtm(*rgb, *lights, options, &stats);
    digests = writeModel<formats::PtmFile>(path, ptm, formats::writePtm, formats::writePtm, ctx.settings.ptmWritten,
                                          output, ctx.settings.threads);
    format = formats::formatName(ptm.format);
    model = fit::makeRelightable(std::move(ptm));
  } else {
    formats::HshFile hsh = fit::fitHsh(*rgb, *lights, options, &stats);
    digests = writeModel<formats::HshFile>(path, hsh, formats::writeRti, formats::writeRti, ctx.settings.hshWritten,
                                          output, ctx.settings.threads);
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
    ctx.carrier.addLog("warning", step.id,  // in core/advice.h's words
                       fit::conditioningWarning(options.basis, static_cast<int>(lights->size()), stats));
  }
  if (stats.rank < fit::basisTerms(options.basis))
    carrier::addWarning(ctx.carrier, step.id,
                        {"the light directions are too alike to determine every term of " + basis +
                             "; where they cannot tell terms apart, the fit takes the smallest model that matches",
                         carrier::Usable::WithCare,
                         "the model shows the surface under lights like the photographed ones, but not under others",
                         "photograph the object again with lights spread over more elevations and directions, or "
                         "use a simpler basis (ptm-lrgb needs 6 well-spread lights, hsh2 4)",
                         "rank " + std::to_string(stats.rank) + " of " + std::to_string(fit::basisTerms(options.basis)) +
                             " terms"});
  if (recorded.holdout > 0) {
    // A near-light model is relit at a direction, not at a pixel's own light and distance: its
    // figure at an unseen light would not be the photograph's. Said, not measured.
    if (nearCount > 0) {
      carrier::addWarning(ctx.carrier, step.id,
                          {basis + " was not measured at the lights left out (--holdout): the lights are near, "
                               "at known positions, and the comparison is made for lights far away",
                           carrier::Usable::Yes, "the fit itself uses every photograph as usual",
                           "nothing; to compare bases at unseen lights, use a capture whose lights are far (or "
                           "leave --holdout out)",
                           "holdout " + std::to_string(recorded.holdout)});
    } else {
      ModelRecipe recipe;
      recipe.basis = basis;
      recipe.threads = ctx.settings.threads;
      measureAndRecordHeldOut(step, ctx, result, recipe, *rgb, *lights, recorded.holdout);
    }
  }
  ctx.put(modelKey(basis), model);
}

}  // namespace surrogate::stages
