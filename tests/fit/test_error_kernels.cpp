// The single-precision fit errors (src/fit/error_kernels.h, RtiFit version 8): each variant
// against the formula of the header written out here in float, bit for bit (so the variants
// against each other); bytes b against their 16-bit values 257 b; the sums against the exact
// error; and whole fits, whose statistics in single precision stay within float's spacing of
// the error the model files give when rendered here from their bytes (the formats' decoding),
// and whose double-precision statistics (version 7) keep to it exactly.
#include <catch2/catch.hpp>

#include <cmath>
#include <cstring>
#include <random>
#include <vector>

#include "fit/error_kernels.h"
#include "fit/fit.h"
#include "reference_basis.h"
#include "synthetic.h"

using namespace surrogate;
using namespace surrogate::fit;

namespace {

constexpr double kR = 0.2126, kG = 0.7152, kB = 0.0722;

std::vector<KernelIsa> variants() {
  std::vector<KernelIsa> out = {KernelIsa::Baseline};
  if (activeKernelIsa() == KernelIsa::Avx2) out.push_back(KernelIsa::Avx2);
  return out;
}

bool sameBits(double a, double b) { return std::memcmp(&a, &b, sizeof a) == 0; }

float clampLevel(float v) { return v < 0.0f ? 0.0f : (v > 255.0f ? 255.0f : v); }

// d of error_kernels.h for one pixel, every step in float.
float differenceOf(const float v[3], const std::uint16_t* s) {
  const float r = static_cast<float>(kR), g = static_cast<float>(kG), b = static_cast<float>(kB);
  const float model = r * clampLevel(v[0]) + g * clampLevel(v[1]) + b * clampLevel(v[2]);
  const float captured = (r * float(s[0]) + g * float(s[1]) + b * float(s[2])) * (1.0f / 257.0f);
  return model - captured;
}

// The header's sum: lanes x mod 8 up to the last multiple of 8, combined pairwise, then the rest.
double laneSum(const std::vector<float>& d) {
  double lane[8] = {0, 0, 0, 0, 0, 0, 0, 0};
  const std::size_t whole = d.size() / 8 * 8;
  for (std::size_t x = 0; x < whole; ++x) lane[x % 8] += double(d[x] * d[x]);
  double sum = ((lane[0] + lane[1]) + (lane[2] + lane[3])) + ((lane[4] + lane[5]) + (lane[6] + lane[7]));
  for (std::size_t x = whole; x < d.size(); ++x) sum += double(d[x] * d[x]);
  return sum;
}

// A row of random planes and samples: values below 0, inside and above 0..255 after the model
// (the clamps), the full 16-bit range of samples.
struct Row {
  Row(std::size_t pixels, int planeCount, unsigned seed) : samples(3 * pixels), planes(planeCount) {
    std::mt19937 random(seed);
    std::uniform_int_distribution<int> sample(0, 65535);
    std::uniform_real_distribution<float> value(-0.3f, 1.4f), colour(0.0f, 255.0f);
    for (auto& s : samples) s = static_cast<std::uint16_t>(sample(random));
    for (int k = 0; k < planeCount; ++k) {
      planes[k].resize(pixels);
      for (float& v : planes[k]) v = k >= 6 && planeCount == 9 ? colour(random) : 255.0f * value(random);
    }
    for (int k = 0; k < planeCount; ++k) pointers.push_back(planes[k].data());
  }
  std::vector<std::uint16_t> samples;
  std::vector<std::vector<float>> planes;
  std::vector<const float*> pointers;
};

std::vector<float> randomBasis(int terms, unsigned seed) {
  std::mt19937 random(seed);
  std::uniform_real_distribution<float> u(-0.6f, 0.9f);
  std::vector<float> b(terms);
  for (float& v : b) v = u(random);
  b[0] = 0.9f;
  return b;
}

// Bytes standing for the samples' high bytes, and the 16-bit values 257 b they stand for.
std::vector<std::uint8_t> asBytes(std::vector<std::uint16_t>& samples) {
  std::vector<std::uint8_t> bytes(samples.size());
  for (std::size_t j = 0; j < samples.size(); ++j) {
    bytes[j] = static_cast<std::uint8_t>(samples[j] >> 8);
    samples[j] = static_cast<std::uint16_t>(257 * bytes[j]);
  }
  return bytes;
}

}  // namespace

TEST_CASE("single-precision LRGB errors follow the formula bit for bit, in every variant", "[fit][errors]") {
  for (std::size_t pixels : {0, 1, 7, 8, 9, 63, 64, 65, 1200}) {
    Row row(pixels, 9, 11 + static_cast<unsigned>(pixels));
    const std::vector<float> basis = randomBasis(6, 3);
    const float* lum[6];
    const float* colour[3];
    for (int k = 0; k < 6; ++k) lum[k] = row.pointers[k];
    for (int c = 0; c < 3; ++c) colour[c] = row.pointers[6 + c];
    std::vector<float> d(pixels);
    for (std::size_t x = 0; x < pixels; ++x) {
      float l = basis[0] * lum[0][x];
      for (int k = 1; k < 6; ++k) l = l + basis[k] * lum[k][x];
      const float t = l * (1.0f / 255.0f);
      const float v[3] = {colour[0][x] * t, colour[1][x] * t, colour[2][x] * t};
      d[x] = differenceOf(v, &row.samples[3 * x]);
    }
    const double expected = laneSum(d);
    std::vector<std::uint16_t> wide = row.samples;
    const std::vector<std::uint8_t> bytes = asBytes(wide);
    for (KernelIsa isa : variants()) {
      INFO(pixels << " pixels, variant " << int(isa));
      CHECK(sameBits(lrgbSquaredErrorSum(lum, colour, basis.data(), row.samples.data(), pixels, isa), expected));
      // Bytes b give what their 16-bit values 257 b give.
      CHECK(sameBits(lrgbSquaredErrorSum(lum, colour, basis.data(), bytes.data(), pixels, isa),
                     lrgbSquaredErrorSum(lum, colour, basis.data(), wide.data(), pixels, isa)));
    }
  }
}

TEST_CASE("single-precision per-channel errors follow the formula bit for bit, in every variant", "[fit][errors]") {
  for (int terms : {4, 6, 9}) {
    for (std::size_t pixels : {1, 8, 13, 200}) {
      Row row(pixels, 3 * terms, 100 + terms + static_cast<unsigned>(pixels));
      const std::vector<float> basis = randomBasis(terms, 5);
      std::vector<float> d(pixels);
      for (std::size_t x = 0; x < pixels; ++x) {
        float v[3];
        for (int c = 0; c < 3; ++c) {
          v[c] = basis[0] * row.planes[c][x];
          for (int k = 1; k < terms; ++k) v[c] = v[c] + basis[k] * row.planes[3 * k + c][x];
        }
        d[x] = differenceOf(v, &row.samples[3 * x]);
      }
      const double expected = laneSum(d);
      std::vector<std::uint16_t> wide = row.samples;
      const std::vector<std::uint8_t> bytes = asBytes(wide);
      for (KernelIsa isa : variants()) {
        INFO(terms << " terms, " << pixels << " pixels, variant " << int(isa));
        CHECK(sameBits(channelSquaredErrorSum(row.pointers.data(), terms, basis.data(), row.samples.data(), pixels, isa),
                       expected));
        CHECK(sameBits(channelSquaredErrorSum(row.pointers.data(), terms, basis.data(), bytes.data(), pixels, isa),
                       channelSquaredErrorSum(row.pointers.data(), terms, basis.data(), wide.data(), pixels, isa)));
      }
    }
  }
}

TEST_CASE("single-precision error sums stay within two millionths of the exact sum", "[fit][errors]") {
  // Model values inside 0..255 and errors of a few levels, as a fit's: the exact sum of the
  // same inputs in long double against the kernel's.
  const std::size_t pixels = 1200;
  std::mt19937 random(21);
  std::uniform_real_distribution<float> level(20.0f, 230.0f), error(-12.0f, 12.0f);
  std::vector<float> planes[3];
  std::vector<std::uint16_t> samples(3 * pixels);
  long double exact = 0;
  for (auto& p : planes) p.resize(pixels);
  for (std::size_t x = 0; x < pixels; ++x) {
    long double model = 0, captured = 0;
    for (int c = 0; c < 3; ++c) {
      planes[c][x] = level(random);
      samples[3 * x + c] = static_cast<std::uint16_t>(std::lround(std::clamp(planes[c][x] + error(random), 0.0f, 255.0f) * 257));
      const long double w = c == 0 ? kR : c == 1 ? kG : kB;
      model += w * planes[c][x];
      captured += w * samples[3 * x + c] / 257.0L;
    }
    exact += (model - captured) * (model - captured);
  }
  const float* pointers[3] = {planes[0].data(), planes[1].data(), planes[2].data()};
  const float basis[1] = {1.0f};
  for (KernelIsa isa : variants()) {
    const double sum = channelSquaredErrorSum(pointers, 1, basis, samples.data(), pixels, isa);
    CHECK(std::abs(sum / double(exact) - 1) < 2e-6);
  }
}

namespace {

// RMSE per image of a PTM relit at `lights` against the stack, computed here from the file's
// bytes by the format's decoding (formats/ptm.h), in long double: the fit's own error, exactly.
std::vector<double> ptmRmse(const formats::PtmFile& ptm, const MemoryImageStack& stack,
                            const std::vector<test::Light>& lights) {
  std::vector<double> out;
  std::vector<std::uint16_t> row(static_cast<std::size_t>(ptm.width) * 3);
  for (std::size_t i = 0; i < lights.size(); ++i) {
    const auto b = fit::ptmBasis(lights[i][0], lights[i][1]);
    long double sum = 0;
    for (int y = 0; y < ptm.height; ++y) {
      stack.readRows(static_cast<int>(i), y, y + 1, row.data());
      for (int x = 0; x < ptm.width; ++x) {
        long double model = 0;
        if (ptm.format == formats::PtmFile::Format::Lrgb) {
          long double l = 0;
          for (int k = 0; k < 6; ++k) l += b[k] * ptm.coefficient(x, y, k);
          for (int c = 0; c < 3; ++c) {
            const long double v = ptm.rgb[(std::size_t(y) * ptm.width + x) * 3 + c] * l / 255;
            model += (c == 0 ? kR : c == 1 ? kG : kB) * std::clamp(v, 0.0L, 255.0L);
          }
        } else {
          for (int c = 0; c < 3; ++c) {
            long double v = 0;
            for (int k = 0; k < 6; ++k) v += b[k] * ptm.coefficient(x, y, k, c);
            model += (c == 0 ? kR : c == 1 ? kG : kB) * std::clamp(v, 0.0L, 255.0L);
          }
        }
        const std::uint16_t* s = &row[3 * std::size_t(x)];
        const long double captured = (kR * s[0] + kG * s[1] + kB * s[2]) / 257.0L;
        sum += (model - captured) * (model - captured);
      }
    }
    out.push_back(double(std::sqrt(sum / ptm.texels())));
  }
  return out;
}

}  // namespace

// Float's spacing near 255 is 1.5e-5 levels: a model value and the captured value each carry
// about that much, so an image's RMSE moves by a few 1e-5 levels at most, however small it is
// (these synthetic fits miss by about 0.1 level, where that is 1e-4 of it; a photograph's
// few levels, a millionth).
constexpr double kFloatLevels = 5e-5;

TEST_CASE("a fit's errors in single precision: the same model, its error within float's spacing", "[fit][errors]") {
  const auto lights = test::spreadLights(20);
  const test::PtmTruth truth = test::randomPtm(67, 9, 41);
  const MemoryImageStack stack = test::ptmImages(truth, lights);
  for (Basis basis : {Basis::PtmLrgb, Basis::PtmRgb}) {
    INFO(basisName(basis));
    FitOptions options;
    options.basis = basis;
    options.threads = 2;
    FitStatistics single, twice;
    options.errors = ErrorMeasure::Lanes;
    const formats::PtmFile a = fitPtm(stack, lights, options, &single);
    options.errors = ErrorMeasure::Serial;
    const formats::PtmFile b = fitPtm(stack, lights, options, &twice);
    CHECK(a == b);  // how the error is summed changes no byte of the model
    const std::vector<double> exact = ptmRmse(a, stack, lights);
    REQUIRE(single.perImageRmse.size() == exact.size());
    for (std::size_t i = 0; i < exact.size(); ++i) {
      INFO("image " << i << ": " << exact[i]);
      CHECK(std::abs(twice.perImageRmse[i] / exact[i] - 1) < 1e-12);
      CHECK(std::abs(single.perImageRmse[i] - exact[i]) < kFloatLevels);
    }
    CHECK(std::abs(single.psnr - twice.psnr) < 1e-4);
  }
}

TEST_CASE("an HSH fit's errors in single precision stay within float's spacing of version 7's", "[fit][errors]") {
  const auto lights = test::spreadLights(16);
  for (int terms : {4, 9}) {
    const test::HshTruth truth = test::randomHsh(35, 6, terms, 17);
    const MemoryImageStack stack = test::hshImages(truth, lights);
    FitOptions options;
    options.basis = terms == 4 ? Basis::Hsh2 : Basis::Hsh3;
    FitStatistics single, twice;
    options.errors = ErrorMeasure::Lanes;
    const formats::HshFile a = fitHsh(stack, lights, options, &single);
    options.errors = ErrorMeasure::Serial;
    const formats::HshFile b = fitHsh(stack, lights, options, &twice);
    CHECK(a == b);
    REQUIRE(single.perImageRmse.size() == twice.perImageRmse.size());
    for (std::size_t i = 0; i < single.perImageRmse.size(); ++i)
      CHECK(std::abs(single.perImageRmse[i] - twice.perImageRmse[i]) < kFloatLevels);
  }
}
