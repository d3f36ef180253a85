#include "fit/normals.h"

#include "fit/basis.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <functional>
#include <vector>

#include "core/parallel.h"
#include "fit/lambert.h"
#include "fit/normal_rows.h"
#include "fit/quantise.h"
#include "fit/row_kernels.h"
#include "fit/sample_lanes.h"
#include "fit/texel.h"

#if defined(__x86_64__) && defined(__GNUC__)
#include <immintrin.h>
#endif

namespace surrogate::fit {

namespace {

// A normal's component -1..1 as 0..65535, rounded half away from zero (roundClamped clamps:
// (v + 1) / 2 outside 0..1 scales to outside 0..65535).
std::uint16_t encodeUnit(double v) {
  return static_cast<std::uint16_t>(detail::roundClamped((v + 1.0) / 2.0 * 65535.0, 65535.0));
}

// An 8-bit value as a 16-bit sample: round(v) clamped to 0..255, times 257.
std::uint16_t encodeByte(double v) { return static_cast<std::uint16_t>(detail::toByte(v) * 257); }

// Runs fn(x, y) over every texel, rows split over threads; returns the sum of fn's results
// (per-row counts added in row order).
int forEachTexel(int width, int height, int threads, const std::function<int(int, int)>& fn) {
  std::vector<int> rowCounts(height, 0);
  parallelFor(static_cast<std::size_t>(height), 8, effectiveThreads(threads),
              [&](std::size_t b, std::size_t e) {
                for (std::size_t y = b; y < e; ++y)
                  for (int x = 0; x < width; ++x) rowCounts[y] += fn(x, static_cast<int>(y));
              });
  int total = 0;
  for (int c : rowCounts) total += c;
  return total;
}

Image normalImage(int w, int h) {
  Image out(w, h, 3);
  out.bitsPerSample = 16;
  out.transfer = Transfer::Linear;
  return out;
}

Image albedoImage(int w, int h) {
  Image out(w, h, 3);
  out.bitsPerSample = 8;
  out.transfer = Transfer::Srgb;
  return out;
}

}  // namespace

std::array<double, 3> ptmNormal(const PtmCoefficients& a, bool* usedFallback) {
  double lu0 = 0, lv0 = 0;
  if (ptmMaximum(a, &lu0, &lv0)) {
    const double r2 = lu0 * lu0 + lv0 * lv0;
    if (r2 > 1) {
      const double r = std::sqrt(r2);
      lu0 /= r;
      lv0 /= r;
    }
    if (usedFallback) *usedFallback = false;
    return {lu0, lv0, std::sqrt(std::max(0.0, 1 - lu0 * lu0 - lv0 * lv0))};
  }
  std::array<double, 3> n;
  normalFromLambert(ptmLambert(a), &n);
  if (usedFallback) *usedFallback = true;
  return n;
}

namespace {
#if defined(__x86_64__) && defined(__GNUC__)
// ptmMaximum and the unit-disc clamp of ptmNormal on four texels at a time, the same operations
// on each value in the same order (no fused multiply-add: "avx2" alone, as in row_kernels.cpp):
// the normal where the maximum exists (maximum[x] = 1), to be found by ptmNormal elsewhere.
// Lanes without a maximum may divide by zero; their values are not used.
__attribute__((target("avx2"))) void maximaAvx2(const double* const lum[6], std::size_t width, double* n0, double* n1,
                                                double* n2, std::uint8_t* maximum) {
  const __m256d zero = _mm256_setzero_pd(), one = _mm256_set1_pd(1.0), two = _mm256_set1_pd(2.0),
                four = _mm256_set1_pd(4.0);
  std::size_t x = 0;
  for (; x + 4 <= width; x += 4) {
    __m256d a[6];
    for (int k = 0; k < 6; ++k) a[k] = _mm256_loadu_pd(lum[k] + x);
    const __m256d d = _mm256_sub_pd(_mm256_mul_pd(_mm256_mul_pd(four, a[0]), a[1]), _mm256_mul_pd(a[2], a[2]));
    __m256d lu = _mm256_div_pd(_mm256_sub_pd(_mm256_mul_pd(a[2], a[4]), _mm256_mul_pd(_mm256_mul_pd(two, a[1]), a[3])), d);
    __m256d lv = _mm256_div_pd(_mm256_sub_pd(_mm256_mul_pd(a[2], a[3]), _mm256_mul_pd(_mm256_mul_pd(two, a[0]), a[4])), d);
    const __m256d ok = _mm256_and_pd(_mm256_cmp_pd(d, zero, _CMP_GT_OQ), _mm256_cmp_pd(a[0], zero, _CMP_LT_OQ));
    const __m256d r2 = _mm256_add_pd(_mm256_mul_pd(lu, lu), _mm256_mul_pd(lv, lv));
    const __m256d outside = _mm256_cmp_pd(r2, one, _CMP_GT_OQ);
    const __m256d r = _mm256_sqrt_pd(r2);
    lu = _mm256_blendv_pd(lu, _mm256_div_pd(lu, r), outside);
    lv = _mm256_blendv_pd(lv, _mm256_div_pd(lv, r), outside);
    // std::max(0.0, v) is v where 0 < v, else +0 (also for -0 and NaN), as maxpd(v, 0) gives.
    const __m256d z2 = _mm256_max_pd(_mm256_sub_pd(_mm256_sub_pd(one, _mm256_mul_pd(lu, lu)), _mm256_mul_pd(lv, lv)), zero);
    _mm256_storeu_pd(n0 + x, lu);
    _mm256_storeu_pd(n1 + x, lv);
    _mm256_storeu_pd(n2 + x, _mm256_sqrt_pd(z2));
    const int bits = _mm256_movemask_pd(ok);
    for (int i = 0; i < 4; ++i) maximum[x + i] = (bits >> i) & 1;
  }
  for (; x < width; ++x) maximum[x] = 0;  // the last texels by ptmNormal
}
#endif
}  // namespace

PtmNormalRow::PtmNormalRow(int width) {
  for (auto& v : lum) v.resize(width);
  for (auto& v : n) v.resize(width);
  maximum_.resize(width);
}

int PtmNormalRow::fill(const formats::PtmFile& ptm, const PtmDecoded& decoded, std::size_t plane, int y) {
  const std::size_t width = static_cast<std::size_t>(ptm.width), row = static_cast<std::size_t>(y) * width;
  for (std::size_t x = 0; x < width; ++x) {
    const PtmCoefficients a = ptmLuminance(ptm, decoded, &ptm.coefficients[(row + x) * 6], plane);
    for (int k = 0; k < 6; ++k) lum[k][x] = a[k];
  }
  std::fill(maximum_.begin(), maximum_.end(), 0);
#if defined(__x86_64__) && defined(__GNUC__)
  if (activeKernelIsa() == KernelIsa::Avx2) {
    const double* const rows[6] = {lum[0].data(), lum[1].data(), lum[2].data(), lum[3].data(), lum[4].data(), lum[5].data()};
    maximaAvx2(rows, width, n[0].data(), n[1].data(), n[2].data(), maximum_.data());
  }
#endif
  int fallbacks = 0;
  for (std::size_t x = 0; x < width; ++x) {
    if (maximum_[x]) continue;
    bool fallback = false;
    const auto v = ptmNormal({lum[0][x], lum[1][x], lum[2][x], lum[3][x], lum[4][x], lum[5][x]}, &fallback);
    fallbacks += fallback ? 1 : 0;
    for (int c = 0; c < 3; ++c) n[c][x] = v[c];
  }
  return fallbacks;
}

namespace {
#if defined(__x86_64__) && defined(__GNUC__)
// detail::roundClamped(v, top) of four values, as integers (fit/sample_lanes.h).
__attribute__((target("avx2"))) inline __m128i roundClampedAvx2(__m256d v, __m256d top) {
  return _mm256_cvttpd_epi32(lanes::roundClampedFour(v, top));
}

// The normal samples (encodeUnit) and the LRGB albedo samples (encodeByte of colour * L(n) / 255)
// of a row's texels four at a time, either map nullptr when not made: the same operations on
// each value in the same order as the loop in ptmMaps, which makes the texels past the
// returned count.
__attribute__((target("avx2"))) int lrgbMapsAvx2(const PtmNormalRow& r, const std::uint8_t* rgb, int width,
                                                 std::uint16_t* normals, std::uint16_t* albedo) {
  const __m256d one = _mm256_set1_pd(1.0), two = _mm256_set1_pd(2.0), unitTop = _mm256_set1_pd(65535.0),
                byteTop = _mm256_set1_pd(255.0);
  const __m128i widen = _mm_set1_epi32(257);
  int x = 0;
  for (; x + 4 <= width; x += 4) {
    const __m256d n0 = _mm256_loadu_pd(r.n[0].data() + x), n1 = _mm256_loadu_pd(r.n[1].data() + x);
    alignas(16) std::int32_t v[3][4];
    if (normals) {
      const __m256d n[3] = {n0, n1, _mm256_loadu_pd(r.n[2].data() + x)};
      for (int c = 0; c < 3; ++c)
        _mm_store_si128(reinterpret_cast<__m128i*>(v[c]),
                        roundClampedAvx2(_mm256_mul_pd(_mm256_div_pd(_mm256_add_pd(n[c], one), two), unitTop), unitTop));
      for (int i = 0; i < 4; ++i)
        for (int c = 0; c < 3; ++c) normals[(x + i) * 3 + c] = static_cast<std::uint16_t>(v[c][i]);
    }
    if (albedo) {
      __m256d a[6];
      for (int k = 0; k < 6; ++k) a[k] = _mm256_loadu_pd(r.lum[k].data() + x);
      // evaluatePtm(a, n0, n1), its terms added from the left.
      __m256d l = _mm256_add_pd(_mm256_mul_pd(_mm256_mul_pd(a[0], n0), n0), _mm256_mul_pd(_mm256_mul_pd(a[1], n1), n1));
      l = _mm256_add_pd(l, _mm256_mul_pd(_mm256_mul_pd(a[2], n0), n1));
      l = _mm256_add_pd(l, _mm256_mul_pd(a[3], n0));
      l = _mm256_add_pd(l, _mm256_mul_pd(a[4], n1));
      l = _mm256_add_pd(l, a[5]);
      const std::uint8_t* q = rgb + 3 * x;
      for (int c = 0; c < 3; ++c) {
        const __m256d colour = _mm256_set_pd(q[9 + c], q[6 + c], q[3 + c], q[c]);
        _mm_store_si128(reinterpret_cast<__m128i*>(v[c]),
                        _mm_mullo_epi32(roundClampedAvx2(_mm256_div_pd(_mm256_mul_pd(colour, l), byteTop), byteTop), widen));
      }
      for (int i = 0; i < 4; ++i)
        for (int c = 0; c < 3; ++c) albedo[(x + i) * 3 + c] = static_cast<std::uint16_t>(v[c][i]);
    }
  }
  return x;
}
#endif

// The normal map and the albedo of a PTM, either of them (nullptr: not made), in one pass: the
// albedo is the model at the normal, so making both together finds each texel's normal once.
// Rows are looped over here rather than through forEachTexel, and the coefficients decoded by
// table: the same values as ptmLuminance and ptmChannel give, in less time (about 12 ms of
// CPU of 1200x800, a std::function call and six conversions a texel).
int ptmMaps(const formats::PtmFile& ptm, Image* normals, Image* albedo, int threads) {
  const bool lrgb = ptm.format == formats::PtmFile::Format::Lrgb;
  const PtmDecoded decoded(ptm);
  const std::size_t plane = ptm.texels() * 6;  // bytes of one channel's coefficients
  std::vector<int> rowCounts(ptm.height, 0);
  parallelFor(static_cast<std::size_t>(ptm.height), 8, effectiveThreads(threads), [&](std::size_t b, std::size_t e) {
    PtmNormalRow normalRow(ptm.width);
    for (std::size_t y = b; y < e; ++y) {
      rowCounts[y] = normalRow.fill(ptm, decoded, plane, static_cast<int>(y));
      const std::size_t row = y * ptm.width;
      int x = 0;
#if defined(__x86_64__) && defined(__GNUC__)
      if ((lrgb || !albedo) && activeKernelIsa() == KernelIsa::Avx2)
        x = lrgbMapsAvx2(normalRow, lrgb ? &ptm.rgb[row * 3] : nullptr, ptm.width, normals ? &normals->pixels[row * 3] : nullptr,
                         albedo ? &albedo->pixels[row * 3] : nullptr);
#endif
      for (; x < ptm.width; ++x) {
        const std::size_t texel = row + x;
        const std::array<double, 3> n{normalRow.n[0][x], normalRow.n[1][x], normalRow.n[2][x]};
        if (normals)
          for (int c = 0; c < 3; ++c) normals->pixels[texel * 3 + c] = encodeUnit(n[c]);
        if (albedo && lrgb) {
          const PtmCoefficients lum{normalRow.lum[0][x], normalRow.lum[1][x], normalRow.lum[2][x],
                                    normalRow.lum[3][x], normalRow.lum[4][x], normalRow.lum[5][x]};
          const double l = evaluatePtm(lum, n[0], n[1]);
          for (int c = 0; c < 3; ++c) albedo->pixels[texel * 3 + c] = encodeByte(ptm.rgb[texel * 3 + c] * l / 255.0);
        } else if (albedo) {
          const std::uint8_t* bytes = &ptm.coefficients[texel * 6];
          for (int c = 0; c < 3; ++c)
            albedo->pixels[texel * 3 + c] = encodeByte(evaluatePtm(decoded(bytes + c * plane), n[0], n[1]));
        }
      }
    }
  });
  int total = 0;
  for (int c : rowCounts) total += c;
  return total;
}
}  // namespace

Image normalMap(const formats::PtmFile& ptm, int* fallbackCount, int threads) {
  Image out = normalImage(ptm.width, ptm.height);
  const int fallbacks = ptmMaps(ptm, &out, nullptr, threads);
  if (fallbackCount) *fallbackCount = fallbacks;
  return out;
}

void normalAndAlbedoMaps(const formats::PtmFile& ptm, Image* normals, Image* albedo, int* fallbackCount,
                         int threads) {
  *normals = normalImage(ptm.width, ptm.height);
  *albedo = albedoImage(ptm.width, ptm.height);
  const int fallbacks = ptmMaps(ptm, normals, albedo, threads);
  if (fallbackCount) *fallbackCount = fallbacks;
}

Image normalMap(const formats::HshFile& hsh, int* fallbackCount, int threads) {
  Image out = normalImage(hsh.width, hsh.height);
  const int fallbacks = forEachTexel(hsh.width, hsh.height, threads, [&](int x, int y) {
    std::array<double, 3> b[3];
    hshLambert(hsh, x, y, b);
    std::array<double, 3> sum{}, n;
    for (int c = 0; c < 3; ++c)
      for (int r = 0; r < 3; ++r) sum[r] += b[c][r] / 3.0;
    const bool ok = normalFromLambert(sum, &n);
    for (int c = 0; c < 3; ++c) out.at(x, y, c) = encodeUnit(n[c]);
    return ok ? 0 : 1;
  });
  if (fallbackCount) *fallbackCount = fallbacks;
  return out;
}

Image albedoMap(const formats::PtmFile& ptm, int threads) {
  Image out = albedoImage(ptm.width, ptm.height);
  ptmMaps(ptm, nullptr, &out, threads);
  return out;
}

Image albedoMap(const formats::HshFile& hsh, int threads) {
  Image out = albedoImage(hsh.width, hsh.height);
  forEachTexel(hsh.width, hsh.height, threads, [&](int x, int y) {
    std::array<double, 3> b[3];
    hshLambert(hsh, x, y, b);
    std::array<double, 3> sum{}, n;
    for (int c = 0; c < 3; ++c)
      for (int r = 0; r < 3; ++r) sum[r] += b[c][r] / 3.0;
    normalFromLambert(sum, &n);  // (0, 0, 1) where there is no normal, as normalMap gives
    double w[16];
    hshBasis(n[0], n[1], n[2], hsh.terms, w);
    for (int c = 0; c < 3; ++c) {
      double v = 0;
      for (int t = 0; t < hsh.terms; ++t) v += w[t] * hsh.coefficient(x, y, c, t);
      out.at(x, y, c) = encodeByte(255 * v);  // 0..255 units, as the PTM's
    }
    return 0;
  });
  return out;
}

}  // namespace surrogate::fit
