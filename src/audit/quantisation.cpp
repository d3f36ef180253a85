// Clipping in a prior model's quantised coefficients, and how its size relates to the
// photographs'.
#include <algorithm>
#include <array>
#include <cmath>

#include "audit/audit.h"
#include "core/text.h"

namespace surrogate::audit {
namespace {

// A plane is clipped when this share of its texels sits at a byte extreme (or outside the
// range its scale and bias can hold). A quantisation from the plane's own range puts only its
// smallest and largest values there: a handful of texels, far below 1% of any image.
constexpr double kClampShare = 0.01;
// A refitted value counts as outside the prior's range beyond this many of the larger of the
// two quantisation steps (rounding and the two tools' fits differ by about one step).
constexpr double kRangeSteps = 2.0;

// How many times the mean count of the two bytes next to an extreme the extreme must hold to
// be a pile of clipped values: the half-width end bin of a smooth distribution holds at most
// about 1.5 times its neighbours' (1.4 for values crowding like a cosine's at its peaks).
constexpr double kSpikeRatio = 4.0;

const char* const kChannelNames[3] = {"red", "green", "blue"};

struct Range {
  double lo, hi, step;
};

Range ptmRange(const formats::PtmFile& ptm, int k) {
  const double a = (0 - ptm.bias[k]) * ptm.scale[k], b = (255 - ptm.bias[k]) * ptm.scale[k];
  return {std::min(a, b), std::max(a, b), std::abs(ptm.scale[k])};
}

Range hshRange(const formats::HshFile& hsh, int k) {
  const double a = hsh.bias[k], b = hsh.scale[k] + hsh.bias[k];
  return {std::min(a, b), std::max(a, b), std::abs(hsh.scale[k]) / 255.0};
}

// Clipping piles values up at an end byte, 0 or 255: a spike, far more texels there than on
// the bytes next to it (a smooth field whose values crowd at an end of its range, as a cosine's
// do, fills the neighbours almost as much).
struct Ends {
  std::array<std::size_t, 256> histogram{};
  bool spikeAt0 = false, spikeAt255 = false;
};

template <typename ByteOf>
Ends endsOf(std::size_t texels, ByteOf byteOf) {
  Ends e;
  for (std::size_t t = 0; t < texels; ++t) ++e.histogram[byteOf(t)];
  auto spike = [&](int end, int inward) {
    const double neighbours = 0.5 * (e.histogram[end + inward] + e.histogram[end + 2 * inward]);
    return e.histogram[end] > 0 && e.histogram[end] > kSpikeRatio * neighbours;
  };
  e.spikeAt0 = spike(0, 1);
  e.spikeAt255 = spike(255, -1);
  return e;
}

// Shares of texels in a spike at byte 0 and 255 where that byte does not stand for zero (a
// black background legitimately stores many zeros, at byte 0 when the range starts at zero).
template <typename ValueOf>
void extremes(PlaneCheck& plane, std::size_t texels, const Ends& e, ValueOf valueOfByte, double step) {
  auto share = [&](int end, bool spike) {
    if (!spike || std::abs(valueOfByte(end)) <= step / 2) return 0.0;
    return static_cast<double>(e.histogram[end]) / static_cast<double>(texels);
  };
  plane.atZero = share(0, e.spikeAt0);
  plane.atFull = share(255, e.spikeAt255);
}

// Share of texels the prior's scale and bias clipped: its byte sits in a spike at the end of
// the range (0 or 255, whichever stands for that end) and Surrogate's refit of the same
// photographs asks for a value beyond it. This finds a bias clamped to stand for zero, which
// `extremes` must leave alone. `refitValue(t)` is the refitted value and `priorUnit(t)` the
// factor that puts the prior's range in the same units at texel t (1, or for LRGB the ratio of
// the two colour sums). Photographs processed otherwise give a refit beyond the prior's range
// too, but with no spike: not counted.
template <typename ByteOf, typename ValueOf, typename UnitOf>
double outside(std::size_t texels, const Range& prior, bool increasing, const Ends& e, double refitStep,
               ByteOf byteOf, ValueOf refitValue, UnitOf priorUnit) {
  const double tol = kRangeSteps * std::max(prior.step, refitStep);
  const bool loSpike = increasing ? e.spikeAt0 : e.spikeAt255, hiSpike = increasing ? e.spikeAt255 : e.spikeAt0;
  const int loByte = increasing ? 0 : 255, hiByte = 255 - loByte;
  std::size_t count = 0;
  for (std::size_t t = 0; t < texels; ++t) {
    const double v = refitValue(t), u = priorUnit(t);
    const int b = byteOf(t);
    count += (loSpike && b == loByte && v < (prior.lo - tol) * u) ||
             (hiSpike && b == hiByte && v > (prior.hi + tol) * u);
  }
  return static_cast<double>(count) / static_cast<double>(texels);
}

// An LRGB luminance is relative to the texel's stored colour (L = 255 (R+G+B) / (C_R+C_G+C_B),
// docs/formats.md), and tools average the colour differently: the prior's range is carried
// into the refit's units by the ratio of the two colour sums. 1 for RGB and for black texels.
double lrgbUnit(const formats::PtmFile& prior, const formats::PtmFile& refit, std::size_t t) {
  if (prior.format != formats::PtmFile::Format::Lrgb) return 1.0;
  const int a = prior.rgb[t * 3] + prior.rgb[t * 3 + 1] + prior.rgb[t * 3 + 2];
  const int b = refit.rgb[t * 3] + refit.rgb[t * 3 + 1] + refit.rgb[t * 3 + 2];
  return a > 0 && b > 0 ? static_cast<double>(a) / b : 1.0;
}

void flag(QuantisationCheck& check, PlaneCheck plane) {
  plane.clamped = plane.atZero >= kClampShare || plane.atFull >= kClampShare || plane.outsideRange >= kClampShare;
  check.clamped = check.clamped || plane.clamped;
  check.planes.push_back(std::move(plane));
}

}  // namespace

QuantisationCheck checkQuantisation(const formats::PtmFile& prior, const formats::PtmFile* refit) {
  QuantisationCheck check;
  const bool comparable = refit && refit->format == prior.format && refit->width == prior.width &&
                          refit->height == prior.height;
  const int channels = prior.format == formats::PtmFile::Format::Rgb ? 3 : 1;
  const std::size_t texels = prior.texels();
  for (int c = 0; c < channels; ++c) {
    for (int k = 0; k < 6; ++k) {
      PlaneCheck plane;
      plane.plane = (channels == 3 ? std::string(kChannelNames[c]) + " a" : std::string("a")) + std::to_string(k);
      const Range range = ptmRange(prior, k);
      auto byteOf = [&](std::size_t t) { return prior.coefficients[(c * texels + t) * 6 + k]; };
      const Ends ends = endsOf(texels, byteOf);
      extremes(plane, texels, ends, [&](int b) { return (b - prior.bias[k]) * prior.scale[k]; }, range.step);
      if (comparable)
        plane.outsideRange = outside(
            texels, range, prior.scale[k] >= 0, ends, std::abs(refit->scale[k]), byteOf,
            [&](std::size_t t) {
              return (refit->coefficients[(c * texels + t) * 6 + k] - refit->bias[k]) * refit->scale[k];
            },
            [&](std::size_t t) { return lrgbUnit(prior, *refit, t); });
      flag(check, std::move(plane));
    }
  }
  return check;
}

QuantisationCheck checkQuantisation(const formats::HshFile& prior, const formats::HshFile* refit) {
  QuantisationCheck check;
  const bool comparable = refit && refit->terms == prior.terms && refit->width == prior.width &&
                          refit->height == prior.height;
  const std::size_t samples = prior.texels() * 3;  // every texel's three channels share the tables
  for (int k = 0; k < prior.terms; ++k) {
    PlaneCheck plane;
    plane.plane = "term " + std::to_string(k);
    const Range range = hshRange(prior, k);
    auto byteOf = [&](std::size_t s) { return prior.coefficients[s * prior.terms + k]; };
    const Ends ends = endsOf(samples, byteOf);
    extremes(plane, samples, ends, [&](int b) { return b / 255.0 * prior.scale[k] + prior.bias[k]; }, range.step);
    if (comparable)
      plane.outsideRange = outside(
          samples, range, prior.scale[k] >= 0, ends, std::abs(refit->scale[k]) / 255.0, byteOf,
          [&](std::size_t s) {
            return refit->coefficients[s * refit->terms + k] / 255.0 * refit->scale[k] + refit->bias[k];
          },
          [](std::size_t) { return 1.0; });
    flag(check, std::move(plane));
  }
  return check;
}

SizeRelation relateSizes(int modelWidth, int modelHeight, int photoWidth, int photoHeight) {
  SizeRelation r;
  r.modelWidth = modelWidth, r.modelHeight = modelHeight;
  r.photoWidth = photoWidth, r.photoHeight = photoHeight;
  if (modelWidth == photoWidth && modelHeight == photoHeight) return r;
  // One factor for both sides; the exporter rounds each side to whole pixels.
  r.scale = static_cast<double>(photoWidth) / modelWidth;
  const bool uniform = std::abs(photoHeight / r.scale - modelHeight) <= 1.0 &&
                       std::abs(photoWidth / (static_cast<double>(photoHeight) / modelHeight) - modelWidth) <= 1.0;
  r.kind = uniform ? SizeRelation::Kind::UniformScale : SizeRelation::Kind::Different;
  return r;
}

std::string SizeRelation::describe() const {
  const std::string model = std::to_string(modelWidth) + " x " + std::to_string(modelHeight);
  const std::string photo = std::to_string(photoWidth) + " x " + std::to_string(photoHeight);
  switch (kind) {
    case Kind::Same: return "the model and the photographs are both " + model;
    case Kind::UniformScale:
      return "the model is " + model + ", the photographs " + photo + " (one scale, " +
             fixedDecimals(scale, 3) + "): compared at the model's size";
    case Kind::Different: break;
  }
  return "the model is " + model + ", the photographs " + photo +
         ": not one scale (another crop or aspect), so the model was not compared with them";
}

}  // namespace surrogate::audit
