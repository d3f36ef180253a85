// The model check: a prior .ptm/.rti rendered at each photograph's prior light and compared
// with the photograph, beside Surrogate's own fit of the same basis (fit/fit.h).
#include <algorithm>
#include <cmath>
#include <memory>
#include <opencv2/imgproc.hpp>

#include "audit/audit.h"
#include "audit/statistics.h"
#include "core/atomic_file.h"
#include "core/error.h"
#include "core/text.h"
#include "fit/fit.h"
#include "fit/render.h"
#include "image/opencv_bridge.h"
#include "image/write.h"

namespace surrogate::audit {
namespace {

const char* const kStep = "audit";

// Mid-tones only for the tone fit: near black and near white the photograph clips, which
// is no evidence of another tone curve.
constexpr double kToneLow = 8.0, kToneHigh = 247.0;
// At most this many (render, photograph) luminance pairs are kept for the tone fit: enough
// for two parameters, and a fixed stride keeps it deterministic.
constexpr std::size_t kToneSamples = 200000;
// A tone difference is reported when gain or gamma is this far from 1 and correcting it
// removes at least half of the error (otherwise the error has another cause).
constexpr double kToneTolerance = 0.03;
constexpr double kToneExplains = 0.5;
// Tone curves that processing gives (exposure within two stops, gamma between a linear and a
// doubly encoded rendering); a fit outside says the error is no tone curve at all.
constexpr double kToneMinGain = 0.25, kToneMaxGain = 4.0, kToneMinGamma = 0.4, kToneMaxGamma = 2.5;


// The photographs at the model's size (a uniform scale): area averaging to shrink, bilinear
// to enlarge, on the values as encoded, as the exporting tools resize.
std::unique_ptr<ImageStack> resizedCopy(const ImageStack& stack, int width, int height) {
  std::vector<Image> images;
  for (int i = 0; i < stack.size(); ++i) {
    const cv::Mat in = image::toMat(readImage(stack, i));
    cv::Mat out;
    const bool shrink = width < stack.width();
    cv::resize(in, out, cv::Size(width, height), 0, 0, shrink ? cv::INTER_AREA : cv::INTER_LINEAR);
    images.push_back(image::fromMat(out, stack.transfer(), 16));
  }
  return std::make_unique<MemoryImageStack>(std::move(images));
}

struct ToneSamples {
  std::size_t stride = 1;
  std::vector<std::pair<double, double>> pairs;  // (render, photograph), 0..255
};

// The model's luminance error against every photograph that has a light, at that light.
ModelErrors errorsOf(const fit::Relightable& model, const ImageStack& photos,
                     const std::vector<std::string>& names,
                     const std::vector<std::optional<Light>>& lights, int threads,
                     ToneSamples* tone) {
  ModelErrors out;
  fit::RenderOptions render;
  render.threads = threads;
  double totalSquares = 0;
  std::size_t totalCount = 0;
  std::vector<double> psnrs;
  for (int i = 0; i < photos.size(); ++i) {
    if (!lights[i]) continue;
    const Image rendered = luminance(model.render(*lights[i], render));
    const Image photo = luminance(readImage(photos, i));
    double squares = 0;
    for (std::size_t p = 0; p < photo.pixels.size(); ++p) {
      const double r = rendered.pixels[p] / 257.0, s = photo.pixels[p] / 257.0;
      squares += (r - s) * (r - s);
      if (tone && (totalCount + p) % tone->stride == 0 && r > kToneLow && r < kToneHigh &&
          s > kToneLow && s < kToneHigh)
        tone->pairs.emplace_back(r, s);
    }
    totalSquares += squares;
    totalCount += photo.pixels.size();
    const double rmse = std::sqrt(squares / static_cast<double>(photo.pixels.size()));
    out.images.push_back({names[i], rmse, psnrOf(rmse), lights[i]});
    psnrs.push_back(out.images.back().psnr);
  }
  if (out.images.empty()) {
    out.note = "no photograph has a light to render at";
    return out;
  }
  out.computed = true;
  out.rmse = std::sqrt(totalSquares / static_cast<double>(totalCount));
  out.psnr = psnrOf(out.rmse);
  out.medianPsnr = median(psnrs);
  const auto worst = std::min_element(out.images.begin(), out.images.end(),
                                      [](const ImageError& a, const ImageError& b) { return a.psnr < b.psnr; });
  out.worstPsnr = worst->psnr;
  out.worstImage = worst->image;
  return out;
}

// p = 255 g (r / 255)^gamma by least squares on the logarithms.
ColourRelation fitTone(const ToneSamples& tone) {
  ColourRelation out;
  if (tone.pairs.size() < 100) return out;
  double sx = 0, sy = 0, sxx = 0, sxy = 0;
  for (const auto& [r, p] : tone.pairs) {
    const double x = std::log(r / 255.0), y = std::log(p / 255.0);
    sx += x, sy += y, sxx += x * x, sxy += x * y;
  }
  const double n = static_cast<double>(tone.pairs.size());
  const double det = n * sxx - sx * sx;
  if (!(std::abs(det) > 1e-12)) return out;
  out.measured = true;
  out.gamma = (n * sxy - sx * sy) / det;
  out.gain = std::exp((sy - out.gamma * sx) / n);
  double before = 0, after = 0;
  for (const auto& [r, p] : tone.pairs) {
    const double corrected = 255.0 * out.gain * std::pow(r / 255.0, out.gamma);
    before += (r - p) * (r - p);
    after += (corrected - p) * (corrected - p);
  }
  out.rmseBefore = std::sqrt(before / n);
  out.rmseAfter = std::sqrt(after / n);
  const bool plausible = out.gain >= kToneMinGain && out.gain <= kToneMaxGain && out.gamma >= kToneMinGamma &&
                         out.gamma <= kToneMaxGamma;
  out.differs = plausible &&
                (std::abs(out.gain - 1) > kToneTolerance || std::abs(out.gamma - 1) > kToneTolerance) &&
                out.rmseAfter <= kToneExplains * out.rmseBefore;
  return out;
}

// The prior model as read, kept for the quantisation check.
struct PriorModel {
  std::optional<formats::PtmFile> ptm;
  std::optional<formats::HshFile> hsh;
  std::unique_ptr<fit::Relightable> relightable;
};

// What the audit holds beside the prior model as read: the copy of it that is relit, and per
// texel the two renderings and the difference picture (16-bit RGB, 6 bytes each), while the
// picture is made its two luminances (2 each), signed differences (4) and 8-bit canvas (3).
constexpr std::uint64_t kAuditBytesPerTexel = 3 * 6 + 2 * 2 + 4 + 3;

// Refused from its header when reading and auditing it would not fit `memory` (--memory; in a
// run, the part a fit may use): a JPEG-compressed PTM of megabytes can declare gigabytes.
PriorModel readPriorModel(const std::filesystem::path& path, std::uint64_t memory, std::uint64_t memoryOption) {
  const std::string bytes = readFile(path, kStep);
  const auto* data = reinterpret_cast<const std::uint8_t*>(bytes.data());
  const formats::ModelBudget budget{memory, kAuditBytesPerTexel, 1, memoryOption};
  PriorModel m;
  if (bytes.compare(0, 4, "PTM_") == 0) {
    m.ptm = formats::parsePtm(data, bytes.size(), path.string(), nullptr, budget);
    m.relightable = fit::makeRelightable(*m.ptm);
  } else if (!bytes.empty() && bytes[0] == '#') {
    m.hsh = formats::parseRti(data, bytes.size(), path.string(), nullptr, budget);
    m.relightable = fit::makeRelightable(*m.hsh);
  } else {
    throwInputError(path.string(), kStep, "is neither a PTM (.ptm) nor an HSH RTI (.rti) file; it cannot be audited");
  }
  return m;
}

// The basis Surrogate refits with, when its fitter has it (HSH order 4 it has not).
std::optional<fit::Basis> refitBasis(const std::string& basis) {
  for (fit::Basis b : {fit::Basis::PtmLrgb, fit::Basis::PtmRgb, fit::Basis::Hsh2, fit::Basis::Hsh3})
    if (basis == fit::basisName(b)) return b;
  return std::nullopt;
}

struct Refit {
  ModelErrors errors;
  std::optional<formats::PtmFile> ptm;
  std::optional<formats::HshFile> hsh;
  std::unique_ptr<fit::Relightable> relightable;
};

// Surrogate's fit of `basis` from the photographs that have a light, then its error at them.
Refit refit(fit::Basis basis, const ImageStack& photos, const std::vector<std::string>& names,
            const std::vector<std::optional<Light>>& lights, const AuditOptions& audit) {
  Refit out;
  std::vector<int> index;
  std::vector<std::array<double, 3>> used;
  for (int i = 0; i < photos.size(); ++i)
    if (lights[i]) index.push_back(i), used.push_back(*lights[i]);
  if (static_cast<int>(index.size()) < fit::basisTerms(basis)) {
    out.errors.note = std::to_string(index.size()) + " photographs with a light, fewer than the " +
                      std::to_string(fit::basisTerms(basis)) + " terms of " + fit::basisName(basis);
    return out;
  }
  const SubsetStack subset(photos, index);
  fit::FitOptions options;
  options.basis = basis;
  options.threads = audit.threads;
  options.memoryBudgetBytes = audit.memoryBudgetBytes;
  if (fit::isPtm(basis)) {
    out.ptm = fit::fitPtm(subset, used, options);
    out.relightable = fit::makeRelightable(*out.ptm);
  } else {
    out.hsh = fit::fitHsh(subset, used, options);
    out.relightable = fit::makeRelightable(*out.hsh);
  }
  out.errors = errorsOf(*out.relightable, photos, names, lights, audit.threads, nullptr);
  return out;
}

// Surrogate's fits of the prior's basis, with the prior's lights and with its own, into
// `check`; the first is returned whole (the quantisation check and the difference image use it).
Refit surrogateFits(ModelCheck& check, const ImageStack& photos, const std::vector<std::string>& names,
                    const std::vector<std::optional<Light>>& priorOfImage, const std::vector<Light>& surrogateLights,
                    const AuditOptions& options) {
  Refit withPrior, withSurrogate;
  const auto basis = refitBasis(check.basis);
  if (basis) {
    withPrior = refit(*basis, photos, names, priorOfImage, options);
    const std::vector<std::optional<Light>> surrogateOfImage(surrogateLights.begin(), surrogateLights.end());
    if (!surrogateLights.empty()) withSurrogate = refit(*basis, photos, names, surrogateOfImage, options);
    else withSurrogate.errors.note = "Surrogate has no lights for these photographs";
  } else {
    withPrior.errors.note = withSurrogate.errors.note = "Surrogate does not fit " + check.basis;
  }
  check.refitPriorLights = withPrior.errors;
  check.refitSurrogateLights = std::move(withSurrogate.errors);
  return withPrior;
}

QuantisationCheck quantisationOf(const PriorModel& prior, const Refit* refit) {
  if (prior.ptm) return checkQuantisation(*prior.ptm, refit && refit->ptm ? &*refit->ptm : nullptr);
  return checkQuantisation(*prior.hsh, refit && refit->hsh ? &*refit->hsh : nullptr);
}

std::string basisOf(const PriorModel& m) {
  if (m.ptm) return m.ptm->format == formats::PtmFile::Format::Lrgb ? "ptm-lrgb" : "ptm-rgb";
  return "hsh" + std::to_string(static_cast<int>(std::lround(std::sqrt(m.hsh->terms))));
}

std::string lightText(const Light& l) {
  return "(" + fixedDecimals(l[0], 3) + ", " + fixedDecimals(l[1], 3) + ", " + fixedDecimals(l[2], 3) + ")";
}

// The photograph the first difference image is made at: the caller's choice, else the worst
// image (ModelErrors::worstImage: the lowest PSNR, the first in stack order among equals).
int differenceIndex(const std::vector<std::optional<Light>>& lights, const std::vector<std::string>& names,
                    const ModelErrors& errors, int requested) {
  if (requested >= 0) {
    if (requested < static_cast<int>(lights.size()) && lights[requested]) return requested;
    throw Error(ErrorKind::Usage, "--difference-image", kStep,
                "photograph " + std::to_string(requested) + " has no prior light; choose another");
  }
  for (int i = 0; i < static_cast<int>(names.size()); ++i)
    if (lights[i] && names[i] == errors.worstImage) return i;
  return -1;
}

// One difference picture of `prior` at photograph `d` (-1: at options.differenceLight), written
// as `file` and added to check.differences.
void writeDifference(ModelCheck& check, const fit::Relightable& prior, const fit::Relightable* refitted,
                     const ImageStack& photos, const std::vector<std::string>& names,
                     const std::vector<std::optional<Light>>& lights, const AuditOptions& options, int d,
                     const std::filesystem::path& file, bool worst) {
  const bool againstFit = options.differenceAgainst == AuditOptions::DifferenceAgainst::SurrogateFit;
  const Light light = d < 0 ? *options.differenceLight : *lights[d];
  fit::RenderOptions render;
  render.threads = options.threads;
  const Image a = prior.render(light, render);
  const Image b = againstFit ? refitted->render(light, render) : readImage(photos, d);
  const std::string against = againstFit ? "Surrogate's fit (prior lights)" : "photograph " + names[d];
  const std::string where = d >= 0 && againstFit ? names[d] + "'s prior light " : "light ";
  const DifferencePicture picture = differencePicture(a, b, "prior minus " + against + ", " + where + lightText(light));
  image::writePng(picture.picture, file);
  DifferenceImage out;
  out.file = file;
  out.image = d < 0 ? std::string() : names[d];
  out.light = light;
  out.fullScale = picture.fullScale;
  out.worst = worst;
  out.description = std::string("prior model minus ") +
                    (againstFit ? "Surrogate's fit (prior lights)" : "the photograph") +
                    (d < 0 ? " at the light " : " " + names[d] + " at its prior light ") + lightText(light) +
                    ", on luminance; blue: prior darker, red: prior brighter, full scale " +
                    formatNumber(picture.fullScale) + " levels";
  check.differences.push_back(std::move(out));
}

// The difference picture at the worst image (or the caller's choice), then one at each image
// options.differenceAt names.
void writeDifferences(ModelCheck& check, const fit::Relightable& prior, const fit::Relightable* refitted,
                      const ImageStack& photos, const std::vector<std::string>& names,
                      const std::vector<std::optional<Light>>& lights, const AuditOptions& options) {
  const bool againstFit = options.differenceAgainst == AuditOptions::DifferenceAgainst::SurrogateFit;
  if (againstFit && !refitted) return;
  const std::string stem = check.file.stem().string();
  const bool atChosenLight = againstFit && options.differenceLight;
  const int d = atChosenLight ? -1 : differenceIndex(lights, names, check.prior, options.differenceImage);
  if (atChosenLight || d >= 0)
    writeDifference(check, prior, refitted, photos, names, lights, options, d,
                    options.differenceFolder / (stem + "-difference.png"), !atChosenLight && options.differenceImage < 0);
  for (int named : options.differenceAt) {
    if (check.lightFile.empty()) break;  // no prior lights: the prior is rendered nowhere
    if (named < 0 || named >= static_cast<int>(lights.size()) || !lights[named])
      throw Error(ErrorKind::Usage, named >= 0 && named < static_cast<int>(names.size()) ? names[named] : "", kStep,
                  "has no light in " + check.lightFile.filename().string() +
                      ", so the prior cannot be rendered at it; name a photograph the light file names");
    const std::string imageStem = std::filesystem::path(names[named]).stem().string();
    writeDifference(check, prior, refitted, photos, names, lights, options, named,
                    options.differenceFolder / (stem + "-difference-" + imageStem + ".png"), false);
  }
}

}  // namespace

ModelCheck checkModel(const std::filesystem::path& model, const Photographs& photographs,
                      const PriorLights& priorLights, const std::vector<Light>& surrogateLights,
                      const AuditOptions& options) {
  const std::size_t n = photographs.files.size();
  if (!photographs.stack || photographs.stack->size() != static_cast<int>(n) ||
      priorLights.lineOfImage.size() != n || (!surrogateLights.empty() && surrogateLights.size() != n))
    throw Error(ErrorKind::Internal, "", kStep, "the photographs, their files and their lights differ in number");
  ModelCheck check;
  check.file = model;
  check.lightFile = priorLights.file;
  PriorModel prior = readPriorModel(model, options.memoryBudgetBytes, options.memoryOption);
  check.basis = basisOf(prior);
  const ImageStack& stack = *photographs.stack;
  check.values = stack.transfer() == Transfer::Linear ? "linear" : "sRGB-encoded";
  check.size = relateSizes(prior.relightable->width(), prior.relightable->height(), stack.width(),
                           stack.height());
  std::vector<std::string> names;
  for (const auto& f : photographs.files) names.push_back(f.filename().string());

  // Every figure is taken at the model's size; another crop is not compared at all.
  std::unique_ptr<ImageStack> resized;
  if (check.size.kind == SizeRelation::Kind::UniformScale)
    resized = resizedCopy(stack, check.size.modelWidth, check.size.modelHeight);
  const ImageStack& photos = resized ? *resized : stack;

  const auto priorOfImage = priorLights.lightOfImage();
  const Refit withPrior = surrogateFits(check, photos, names, priorOfImage, surrogateLights, options);

  if (check.size.kind == SizeRelation::Kind::Different) {
    check.prior.note = check.size.describe();
    check.quantisation = quantisationOf(prior, nullptr);
    return check;
  }
  ToneSamples tone;
  const std::size_t pixels = static_cast<std::size_t>(photos.width()) * photos.height() * photos.size();
  tone.stride = std::max<std::size_t>(1, pixels / kToneSamples);
  check.prior = errorsOf(*prior.relightable, photos, names, priorOfImage, options.threads, &tone);
  if (priorLights.file.empty()) check.prior.note = "no prior light file to render it at";
  check.colour = fitTone(tone);
  check.quantisation = quantisationOf(prior, &withPrior);
  if (!options.differenceFolder.empty())
    writeDifferences(check, *prior.relightable, withPrior.relightable.get(), photos, names, priorOfImage, options);
  return check;
}

}  // namespace surrogate::audit
