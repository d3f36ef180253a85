// The fits' row kernels (src/fit/row_kernels.h): each variant against the plain scalar loops
// written out here from the formulas (docs/hrti-math.md, "What the fit minimises"), bit for bit,
// and so the variants against each other.
#include <catch2/catch.hpp>

#include <Eigen/Core>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <limits>
#include <random>
#include <vector>

#include "fit/row_kernels.h"

using namespace surrogate;
using namespace surrogate::fit;

namespace {

constexpr double kR = 0.2126, kG = 0.7152, kB = 0.0722;

bool sameBits(const std::vector<double>& a, const std::vector<double>& b) {
  return a.size() == b.size() && std::memcmp(a.data(), b.data(), a.size() * sizeof(double)) == 0;
}

std::vector<KernelIsa> variants() {
  std::vector<KernelIsa> out = {KernelIsa::Baseline};
  if (activeKernelIsa() == KernelIsa::Avx2) out.push_back(KernelIsa::Avx2);
  return out;
}

const char* name(KernelIsa isa) { return isa == KernelIsa::Avx2 ? "avx2" : "baseline"; }

// (model - captured)^2, the captured luminance of one pixel's 16-bit samples in 0..255 units.
double squaredError(double model, const std::uint16_t* s) {
  const double captured = (kR * s[0] + kG * s[1] + kB * s[2]) / 257.0;
  return (model - captured) * (model - captured);
}

// Samples over the whole 16-bit range and model values below 0, inside and above 0..255
// (the clamps), with an odd pixel count (the vector loops' tails).
struct Row {
  explicit Row(std::size_t pixels, unsigned seed) : samples(3 * pixels), model(3 * pixels) {
    std::mt19937 random(seed);
    std::uniform_int_distribution<int> sample(0, 65535);
    std::uniform_real_distribution<double> value(-40.0, 300.0);
    for (auto& s : samples) s = static_cast<std::uint16_t>(sample(random));
    for (auto& m : model) m = value(random);
    for (std::size_t j = 0; j < std::min<std::size_t>(12, model.size()); ++j) model[j] = (j % 2 ? -0.0 : 255.0);
    samples[0] = 0;
    samples[1] = 65535;
  }
  std::vector<std::uint16_t> samples;
  std::vector<double> model;
};

}  // namespace

TEST_CASE("the per-channel error kernel gives the squared luminance errors of the clamped model, in every variant") {
  const std::size_t pixels = 1001;
  const Row row(pixels, 7);
  std::vector<double> expected(pixels);
  for (std::size_t x = 0; x < pixels; ++x) {
    const double r = std::clamp(row.model[3 * x], 0.0, 255.0), g = std::clamp(row.model[3 * x + 1], 0.0, 255.0),
                 b = std::clamp(row.model[3 * x + 2], 0.0, 255.0);
    expected[x] = squaredError(kR * r + kG * g + kB * b, &row.samples[3 * x]);
  }
  for (const KernelIsa isa : variants()) {
    INFO("variant " << name(isa));
    std::vector<double> d2(pixels, -1);
    squaredErrorsRgb(row.model.data(), row.samples.data(), pixels, d2.data(), isa);
    CHECK(sameBits(d2, expected));
  }
}

TEST_CASE("the per-channel error kernel reads 8-bit samples as their 16-bit values 257 b, in every variant") {
  const std::size_t pixels = 1003;  // the vector loops' tails
  const Row row(pixels, 5);
  std::vector<std::uint8_t> bytes(3 * pixels);
  std::vector<std::uint16_t> wide(3 * pixels);
  for (std::size_t j = 0; j < bytes.size(); ++j) {
    bytes[j] = static_cast<std::uint8_t>(j < 6 ? (j % 2 ? 255 : 0) : row.samples[j] >> 8);  // both ends of the range
    wide[j] = static_cast<std::uint16_t>(257 * bytes[j]);
  }
  std::vector<double> expected(pixels);
  for (std::size_t x = 0; x < pixels; ++x) {
    const double r = std::clamp(row.model[3 * x], 0.0, 255.0), g = std::clamp(row.model[3 * x + 1], 0.0, 255.0),
                 b = std::clamp(row.model[3 * x + 2], 0.0, 255.0);
    expected[x] = squaredError(kR * r + kG * g + kB * b, &wide[3 * x]);
  }
  for (const KernelIsa isa : variants()) {
    INFO("variant " << name(isa));
    std::vector<double> d2(pixels, -1);
    squaredErrorsRgb(row.model.data(), bytes.data(), pixels, d2.data(), isa);
    CHECK(sameBits(d2, expected));
  }
}

TEST_CASE("the LRGB error kernel gives the squared luminance errors of colour times luminance, in every variant") {
  const std::size_t pixels = 999;
  const Row row(pixels, 11);
  // Six decoded coefficient planes (the luminance polynomial) and their basis at one light.
  const std::size_t stride = pixels + 5;
  std::vector<double> decoded(6 * stride);
  std::mt19937 random(5);
  std::uniform_real_distribution<double> coefficient(-9000.0, 40000.0);
  for (double& v : decoded) v = coefficient(random);
  const double basis[6] = {0.31, -0.27, 0.093, 0.5, -0.61, 1.0};
  std::vector<double> cr(pixels), cg(pixels), cb(pixels), models(pixels);
  for (std::size_t x = 0; x < pixels; ++x) {  // colour bytes
    cr[x] = std::round(std::clamp(row.model[3 * x], 0.0, 255.0));
    cg[x] = std::round(std::clamp(row.model[3 * x + 1], 0.0, 255.0));
    cb[x] = std::round(std::clamp(row.model[3 * x + 2], 0.0, 255.0));
    double l = 0;
    for (int k = 0; k < 6; ++k) l += basis[k] * decoded[k * stride + x];
    double model = 0;
    model += kR * std::clamp(cr[x] * l / 255.0, 0.0, 255.0);
    model += kG * std::clamp(cg[x] * l / 255.0, 0.0, 255.0);
    model += kB * std::clamp(cb[x] * l / 255.0, 0.0, 255.0);
    models[x] = model;
  }
  // 16-bit samples, and 8-bit ones (taken as 257 b) with both ends of their range.
  std::vector<std::uint8_t> bytes(3 * pixels);
  std::vector<std::uint16_t> wide(3 * pixels);
  for (std::size_t j = 0; j < bytes.size(); ++j) {
    bytes[j] = static_cast<std::uint8_t>(j < 6 ? (j % 2 ? 255 : 0) : row.samples[j] >> 8);
    wide[j] = static_cast<std::uint16_t>(257 * bytes[j]);
  }
  std::vector<double> expected16(pixels), expected8(pixels);
  for (std::size_t x = 0; x < pixels; ++x) {
    expected16[x] = squaredError(models[x], &row.samples[3 * x]);
    expected8[x] = squaredError(models[x], &wide[3 * x]);
  }
  for (const KernelIsa isa : variants()) {
    INFO("variant " << name(isa));
    std::vector<double> d2(pixels, -1);
    squaredErrorsLrgb(cr.data(), cg.data(), cb.data(), decoded.data(), stride, basis, row.samples.data(), pixels,
                      d2.data(), isa);
    CHECK(sameBits(d2, expected16));
    squaredErrorsLrgb(cr.data(), cg.data(), cb.data(), decoded.data(), stride, basis, bytes.data(), pixels,
                      d2.data(), isa);
    CHECK(sameBits(d2, expected8));
  }
}

TEST_CASE("the LRGB accumulation adds every photograph in order over the pixels asked for, in every variant") {
  const int n = 9;
  const std::size_t w = 203, x0 = 17, x1 = 190;
  std::vector<Row> rows;
  std::vector<const std::uint16_t*> images;
  for (int i = 0; i < n; ++i) rows.emplace_back(w, 100 + i);
  for (const Row& r : rows) images.push_back(r.samples.data());
  std::mt19937 random(3);
  std::uniform_real_distribution<double> coefficient(-0.01, 0.01);
  std::vector<double> p(6 * n), weight(n);
  for (double& v : p) v = coefficient(random);
  for (int i = 0; i < n; ++i) weight[i] = i == 4 ? 0.0 : 0.001 * (i + 1);  // one light weighs nothing

  // Start from non-zero sums: the kernel adds to what is there.
  std::vector<double> accStart(6 * w), meanStart(3 * w);
  for (std::size_t j = 0; j < accStart.size(); ++j) accStart[j] = 0.5 * j;
  for (std::size_t j = 0; j < meanStart.size(); ++j) meanStart[j] = 0.25 * j;
  std::vector<double> acc = accStart, mean = meanStart;
  for (int i = 0; i < n; ++i) {
    const std::uint16_t* s = images[i];
    for (std::size_t x = x0; x < x1; ++x) {
      const double sum = static_cast<double>(s[3 * x] + s[3 * x + 1] + s[3 * x + 2]);
      for (int k = 0; k < 6; ++k) acc[k * w + x] += p[k * n + i] * sum;
      if (weight[i] != 0)
        for (int c = 0; c < 3; ++c) mean[3 * x + c] += weight[i] * s[3 * x + c];
    }
  }
  for (const KernelIsa isa : variants()) {
    INFO("variant " << name(isa));
    std::vector<double> a = accStart, m = meanStart, scratch(w);
    accumulateLrgb(images.data(), n, w, x0, x1, p.data(), weight.data(), a.data(), m.data(), scratch.data(), isa);
    CHECK(sameBits(a, acc));  // pixels outside [x0, x1) untouched
    CHECK(sameBits(m, mean));
  }
}

TEST_CASE("the quantisation kernels give the bytes and decoded values of the scalar quantisers, in every variant") {
  // Values below, inside and above the range, exact halves (rounding away from zero), huge
  // values and NaN (byte 0).
  std::vector<double> a = {-1e300, -7.5, -0.0, 0.0, 1e-300, 12.5, 13.5, 99.49999999999999, 254.5, 255, 1e300,
                           std::numeric_limits<double>::quiet_NaN()};
  std::mt19937 random(17);
  std::uniform_real_distribution<double> value(-50.0, 400.0);
  for (int j = 0; j < 301; ++j) a.push_back(value(random));

  const PtmQuantisation ptm = choosePtmQuantisation(-40.0, 310.0);
  const HshQuantisation hsh = chooseHshQuantisation(-40.0, 310.0);
  // Closed form for one value: with scale 350/255 and bias round(40 / scale) = 29, 12.5 maps to
  // round(12.5 / scale + 29) = round(38.107...) = 38.
  REQUIRE(ptm.bias == 29);
  CHECK(ptm.quantise(12.5) == 38);
  for (const KernelIsa isa : variants()) {
    INFO("variant " << name(isa));
    std::vector<std::uint8_t> bytes(a.size());
    std::vector<double> decoded(a.size());
    quantisePtm(a.data(), a.size(), ptm, bytes.data(), decoded.data(), isa);
    bool same = true;
    for (std::size_t j = 0; j < a.size(); ++j) {
      const std::uint8_t b = ptm.quantise(a[j]);
      const double d = ptm.decode(b);
      same = same && bytes[j] == b && std::memcmp(&decoded[j], &d, sizeof d) == 0;
    }
    CHECK(same);
    CHECK(bytes[5] == 38);  // 12.5

    quantiseHsh(a.data(), a.size(), hsh, bytes.data(), decoded.data(), isa);
    same = true;
    for (std::size_t j = 0; j < a.size(); ++j) {
      const std::uint8_t b = hsh.quantise(a[j]);
      const double d = hsh.decode(b);
      same = same && bytes[j] == b && std::memcmp(&decoded[j], &d, sizeof d) == 0;
    }
    CHECK(same);
    CHECK(bytes[11] == 0);  // NaN

    // A coefficient with one value over the image: every byte 0, decoded to that value.
    const HshQuantisation flat = chooseHshQuantisation(0.25, 0.25);
    quantiseHsh(a.data(), a.size(), flat, bytes.data(), decoded.data(), isa);
    CHECK(std::all_of(bytes.begin(), bytes.end(), [](std::uint8_t b) { return b == 0; }));
    CHECK(std::all_of(decoded.begin(), decoded.end(), [](double d) { return d == 0.25; }));
  }

  // The same values with the special ones last, where the vector loops leave their tails.
  std::rotate(a.begin(), a.begin() + 12, a.end());
  for (const KernelIsa isa : variants()) {
    INFO("variant " << name(isa) << ", special values last");
    std::vector<std::uint8_t> bytes(a.size());
    std::vector<double> decoded(a.size());
    const auto same = [&](const auto& q) {
      bool ok = true;
      for (std::size_t j = 0; j < a.size(); ++j) {
        const std::uint8_t b = q.quantise(a[j]);
        const double d = q.decode(b);
        ok = ok && bytes[j] == b && std::memcmp(&decoded[j], &d, sizeof d) == 0;
      }
      return ok;
    };
    quantisePtm(a.data(), a.size(), ptm, bytes.data(), decoded.data(), isa);
    CHECK(same(ptm));
    quantiseHsh(a.data(), a.size(), hsh, bytes.data(), decoded.data(), isa);
    CHECK(same(hsh));
  }
}

namespace {

// The block product written from its formula: each sum from +0, in column order, then 0 + sum.
template <typename Sample>
std::vector<double> blockProduct(const std::vector<double>& m, int rows, int cols, const std::vector<const Sample*>& src,
                                 std::size_t offset, std::size_t outStride) {
  std::vector<double> out(rows * outStride, -7.0);
  for (int r = 0; r < rows; ++r)
    for (std::size_t j = 0; j < kProductBlock; ++j) {
      double sum = 0.0;
      for (int c = 0; c < cols; ++c) sum += m[r * cols + c] * static_cast<double>(src[c][offset + j]);
      out[r * outStride + j] = 0.0 + sum;
    }
  return out;
}

}  // namespace

TEST_CASE("the block products add every column in order from zero, in every variant, as Eigen's product does") {
  using RowMajor = Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor>;
  std::mt19937 random(11);
  std::uniform_int_distribution<int> sample(0, 65535);
  std::uniform_real_distribution<double> coefficient(-1.0, 1.0);
  const std::size_t offset = 3 * 97, width = offset + kProductBlock + 5;
  // The fits' shapes: T = 4, 6, 9 (16 for HSH of order 4) against N photographs, and back.
  for (const int rows : {1, 2, 3, 4, 5, 6, 7, 9, 12, 16, 36}) {
    for (const int cols : {1, 4, 6, 9, 16, 36, 37, 101, 300}) {
      INFO(rows << " x " << cols);
      std::vector<double> m(static_cast<std::size_t>(rows) * cols);
      for (double& v : m) v = coefficient(random) / 65535.0;
      m[0] = -1.0;  // with a zero sample first: -0 + ... the sums start from +0
      std::vector<std::vector<std::uint16_t>> samples(cols, std::vector<std::uint16_t>(width));
      std::vector<std::vector<double>> values(cols, std::vector<double>(width));
      for (int c = 0; c < cols; ++c)
        for (std::size_t j = 0; j < width; ++j) {
          samples[c][j] = static_cast<std::uint16_t>(sample(random));
          values[c][j] = coefficient(random) * 300.0;
        }
      samples[0][offset] = 0;
      values[0][offset] = 0.0;
      std::vector<const std::uint16_t*> s16;
      std::vector<const double*> sd;
      for (int c = 0; c < cols; ++c) {
        s16.push_back(samples[c].data());
        sd.push_back(values[c].data());
      }
      const std::size_t outStride = kProductBlock + 3;
      const std::vector<double> expected16 = blockProduct(m, rows, cols, s16, offset, outStride);
      const std::vector<double> expectedD = blockProduct(m, rows, cols, sd, offset, outStride);
      if (rows == 1 && cols == 1) CHECK(!std::signbit(expected16[0]));  // 0 + (-1 * 0) is +0

      // Eigen's product of the same matrices, as the fits computed every block before: it
      // adds the same way for whole blocks at the fits' shapes (T of 3 or more rows; up to the
      // columns its blocking keeps in one pass, several hundred).
      if (rows >= 3) {
        Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor> block(cols, kProductBlock);
        for (int c = 0; c < cols; ++c)
          for (std::size_t j = 0; j < kProductBlock; ++j) block(c, j) = samples[c][offset + j];
        RowMajor product(rows, kProductBlock);
        product.noalias() = Eigen::Map<const RowMajor>(m.data(), rows, cols) * block;
        bool same = true;
        for (int r = 0; r < rows; ++r)
          same = same && std::memcmp(&product(r, 0), &expected16[r * outStride], kProductBlock * sizeof(double)) == 0;
        CHECK(same);
      }

      for (const KernelIsa isa : variants()) {
        INFO("variant " << name(isa));
        std::vector<double> out(rows * outStride, -7.0);  // the gaps between the rows stay as they are
        multiplyBlock(m.data(), rows, cols, s16.data(), offset, out.data(), outStride, isa);
        CHECK(sameBits(out, expected16));
        std::fill(out.begin(), out.end(), -7.0);
        multiplyBlock(m.data(), rows, cols, sd.data(), offset, out.data(), outStride, isa);
        CHECK(sameBits(out, expectedD));
      }
    }
  }
}

TEST_CASE("every kernel gives the same bits for bytes as for their 16-bit values 257 b, in every variant") {
  // Photographs of 8-bit sources held as bytes (stream_fit.h RowView::bytes): the kernels read
  // them as the 16-bit values readRows would give, which the tests above check against the
  // formulas.
  const int n = 7;
  const std::size_t w = 403;  // two whole product blocks of samples, ragged ends everywhere
  std::mt19937 random(17);
  std::uniform_int_distribution<int> byte(0, 255);
  std::vector<std::vector<std::uint8_t>> bytes(n, std::vector<std::uint8_t>(3 * w));
  std::vector<std::vector<std::uint16_t>> wide(n, std::vector<std::uint16_t>(3 * w));
  std::vector<const std::uint8_t*> bytePointers;
  std::vector<const std::uint16_t*> widePointers;
  for (int i = 0; i < n; ++i) {
    for (std::size_t j = 0; j < 3 * w; ++j) {
      bytes[i][j] = static_cast<std::uint8_t>(j < 6 ? (i % 2 ? 255 : 0) : byte(random));  // both ends of the range
      wide[i][j] = static_cast<std::uint16_t>(bytes[i][j] * 257);
    }
    bytePointers.push_back(bytes[i].data());
    widePointers.push_back(wide[i].data());
  }
  const Row model(w, 23);
  std::uniform_real_distribution<double> coefficient(-0.01, 0.01);
  std::vector<double> p(6 * n), weight(n), decoded(6 * w);
  for (double& v : p) v = coefficient(random);
  for (int i = 0; i < n; ++i) weight[i] = i == 2 ? 0.0 : 0.001 * (i + 1);
  for (double& v : decoded) v = coefficient(random) * 1e6;
  const double basis[6] = {0.31, -0.27, 0.093, 0.5, -0.61, 1.0};
  std::vector<double> planes(3 * w);
  for (std::size_t j = 0; j < planes.size(); ++j) planes[j] = static_cast<double>(byte(random));

  for (const KernelIsa isa : variants()) {
    INFO("variant " << name(isa));
    std::vector<double> fromBytes(w, -1), fromWide(w, -1);
    squaredErrorsRgb(model.model.data(), bytes[3].data(), w, fromBytes.data(), isa);
    squaredErrorsRgb(model.model.data(), wide[3].data(), w, fromWide.data(), isa);
    CHECK(sameBits(fromBytes, fromWide));

    squaredErrorsLrgb(planes.data(), planes.data() + w, planes.data() + 2 * w, decoded.data(), w, basis,
                      bytes[4].data(), w, fromBytes.data(), isa);
    squaredErrorsLrgb(planes.data(), planes.data() + w, planes.data() + 2 * w, decoded.data(), w, basis,
                      wide[4].data(), w, fromWide.data(), isa);
    CHECK(sameBits(fromBytes, fromWide));

    std::vector<double> accBytes(6 * w, 0.5), meanBytes(3 * w, 0.25), accWide = accBytes, meanWide = meanBytes,
                        scratch(w);
    accumulateLrgb(bytePointers.data(), n, w, 5, w - 3, p.data(), weight.data(), accBytes.data(), meanBytes.data(),
                   scratch.data(), isa);
    accumulateLrgb(widePointers.data(), n, w, 5, w - 3, p.data(), weight.data(), accWide.data(), meanWide.data(),
                   scratch.data(), isa);
    CHECK(sameBits(accBytes, accWide));
    CHECK(sameBits(meanBytes, meanWide));

    for (const std::size_t offset : {std::size_t(0), std::size_t(3 * w - kProductBlock)}) {
      std::vector<double> productBytes(6 * kProductBlock), productWide(6 * kProductBlock);
      multiplyBlock(p.data(), 6, n, bytePointers.data(), offset, productBytes.data(), kProductBlock, isa);
      multiplyBlock(p.data(), 6, n, widePointers.data(), offset, productWide.data(), kProductBlock, isa);
      CHECK(sameBits(productBytes, productWide));
    }
  }
}

TEST_CASE("the range kernel gives what std::min_element and std::max_element give, zeros and NaN included") {
  std::mt19937 random(29);
  std::uniform_real_distribution<double> value(-5.0, 5.0);
  const double nan = std::numeric_limits<double>::quiet_NaN(), inf = std::numeric_limits<double>::infinity();
  // Rows of every length to past two vector steps, then with signed zeros as the extremes
  // (which zero comes first decides the bits), NaN at the start, inside and at the end, and
  // infinities.
  std::vector<std::vector<double>> rows;
  for (std::size_t n = 1; n <= 21; ++n) {
    std::vector<double> a(n);
    for (auto& v : a) v = value(random);
    rows.push_back(a);
  }
  for (const std::size_t n : {1u, 3u, 8u, 9u, 16u, 19u}) {
    for (std::size_t at = 0; at < n; ++at)
      for (const double z : {-0.0, 0.0}) {
        std::vector<double> pos(n), neg(n);
        for (std::size_t j = 0; j < n; ++j) {
          pos[j] = 1.0 + static_cast<double>(j);
          neg[j] = -pos[j];
        }
        pos[at] = neg[at] = z;
        for (std::size_t j = at + 1; j < n; j += 3) pos[j] = neg[j] = (j % 2 ? 0.0 : -0.0);
        rows.push_back(pos);
        rows.push_back(neg);
        std::vector<double> withNan = pos;
        withNan[at] = nan;
        rows.push_back(withNan);
      }
  }
  rows.push_back({inf, -inf, 3.0, 0.0, -0.0, 1e300, -1e-300, 2.0, 5.0});
  rows.push_back({-0.0, -0.0, 0.0, -0.0, 0.0, 0.0, -0.0, 0.0, 0.0, -0.0});
  rows.push_back({0.0, -0.0, 0.0, -0.0, 0.0, 0.0, -0.0, 0.0, 0.0, -0.0, 0.0});
  for (const KernelIsa isa : variants()) {
    INFO("variant " << name(isa));
    bool same = true;
    for (const auto& a : rows) {
      double lo = 7, hi = 7;
      rangeOf(a.data(), a.size(), &lo, &hi, isa);
      const double wantLo = *std::min_element(a.begin(), a.end()), wantHi = *std::max_element(a.begin(), a.end());
      same = same && std::memcmp(&lo, &wantLo, sizeof lo) == 0 && std::memcmp(&hi, &wantHi, sizeof hi) == 0;
    }
    CHECK(same);
  }
}
