#include "fit/row_kernels.h"

#include <algorithm>

#if defined(__x86_64__) && defined(__GNUC__)
#include <immintrin.h>
#endif

#include "core/cpu_features.h"
#include "fit/sample_lanes.h"
#include "fit/stream_fit.h"

// This file is compiled with -fno-trapping-math (src/fit/CMakeLists.txt): it lets the
// compiler turn the clamps into vector selects. It changes no value, only what may happen to
// floating-point exception flags, which nothing reads.

namespace surrogate::fit {

namespace {

// What the block products multiply: the samples' values (row_kernels.h), the decoded
// coefficients as they are.
inline double productValue(std::uint16_t s) { return sampleValue(s); }
inline double productValue(std::uint8_t b) { return sampleValue(b); }
inline double productValue(double v) { return v; }

// clamp(v, 0, 255) as std::clamp computes it (NaN passes through), written on values so that
// it vectorises.
inline double clamp255(double v) {
  const double low = v < 0.0 ? 0.0 : v;
  return 255.0 < low ? 255.0 : low;
}

// The operations and their order per value are the whole contract (see the header).
template <typename Sample>
__attribute__((always_inline)) inline void lrgbBody(const double* __restrict cr, const double* __restrict cg,
                                                    const double* __restrict cb, const double* __restrict decoded,
                                                    std::size_t stride, const double* basis,
                                                    const Sample* __restrict s, std::size_t pixels,
                                                    double* __restrict d2) {
  const double b0 = basis[0], b1 = basis[1], b2 = basis[2], b3 = basis[3], b4 = basis[4], b5 = basis[5];
  for (std::size_t x = 0; x < pixels; ++x) {
    double l = 0;
    l += b0 * decoded[x];
    l += b1 * decoded[stride + x];
    l += b2 * decoded[2 * stride + x];
    l += b3 * decoded[3 * stride + x];
    l += b4 * decoded[4 * stride + x];
    l += b5 * decoded[5 * stride + x];
    double model = 0;
    model += kLumR * clamp255(cr[x] * l / 255.0);
    model += kLumG * clamp255(cg[x] * l / 255.0);
    model += kLumB * clamp255(cb[x] * l / 255.0);
    const double captured =
        (kLumR * sampleValue(s[3 * x]) + kLumG * sampleValue(s[3 * x + 1]) + kLumB * sampleValue(s[3 * x + 2])) /
        257.0;
    d2[x] = (model - captured) * (model - captured);
  }
}

template <typename Sample>
__attribute__((always_inline)) inline void rgbBody(const double* __restrict p, const Sample* __restrict s,
                                                   std::size_t pixels, double* __restrict d2) {
  for (std::size_t x = 0; x < pixels; ++x) {
    const double r = clamp255(p[3 * x]);
    const double g = clamp255(p[3 * x + 1]);
    const double b = clamp255(p[3 * x + 2]);
    const double model = kLumR * r + kLumG * g + kLumB * b;
    const double captured =
        (kLumR * sampleValue(s[3 * x]) + kLumG * sampleValue(s[3 * x + 1]) + kLumB * sampleValue(s[3 * x + 2])) /
        257.0;
    d2[x] = (model - captured) * (model - captured);
  }
}

template <typename Sample>
__attribute__((always_inline)) inline void accumulateBody(const Sample* const* images, int n,
                                                          std::size_t w, std::size_t x0, std::size_t x1,
                                                          const double* p, const double* weight,
                                                          double* __restrict acc, double* __restrict mean,
                                                          double* __restrict sum) {
  for (int i = 0; i < n; ++i) {
    const Sample* __restrict s = images[i];
    for (std::size_t x = x0; x < x1; ++x)
      sum[x] = static_cast<double>(sampleValue(s[3 * x]) + sampleValue(s[3 * x + 1]) + sampleValue(s[3 * x + 2]));
    for (int k = 0; k < 6; ++k) {
      const double pk = p[static_cast<std::size_t>(k) * n + i];
      double* __restrict a = acc + k * w;
      for (std::size_t x = x0; x < x1; ++x) a[x] += pk * sum[x];
    }
    const double wi = weight[i];
    if (wi != 0)
      for (std::size_t j = 3 * x0; j < 3 * x1; ++j) mean[j] += wi * sampleValue(s[j]);
  }
}

// The quantisers themselves (fit/quantise.h: PtmQuantisation, HshQuantisation), a row at a time.
template <typename Quantisation>
__attribute__((always_inline)) inline void quantiseBody(const double* __restrict a, std::size_t count,
                                                        const Quantisation q, std::uint8_t* __restrict bytes,
                                                        double* __restrict decoded) {
  for (std::size_t j = 0; j < count; ++j) {
    const std::uint8_t b = q.quantise(a[j]);
    bytes[j] = b;
    decoded[j] = q.decode(b);
  }
}

// multiplyBlock's sums, written plainly: the baseline variant.
template <typename Sample>
__attribute__((always_inline)) inline void multiplyBody(const double* m, int rows, int cols, const Sample* const* src,
                                                        std::size_t offset, double* out, std::size_t outStride) {
  for (int r = 0; r < rows; ++r) {
    double* __restrict o = out + r * outStride;
    for (std::size_t j = 0; j < kProductBlock; ++j) o[j] = 0.0;
    for (int c = 0; c < cols; ++c) {
      const double mc = m[static_cast<std::size_t>(r) * cols + c];
      const Sample* __restrict s = src[c] + offset;
      for (std::size_t j = 0; j < kProductBlock; ++j) o[j] += mc * productValue(s[j]);
    }
    for (std::size_t j = 0; j < kProductBlock; ++j) o[j] = 0.0 + o[j];
  }
}


// The LRGB accumulation and the block products, written with intrinsics: the accumulators stay
// in registers while every photograph is added, where the compiled bodies load and store them
// once per photograph.
#if defined(__x86_64__) && defined(__GNUC__)
// Eight samples as doubles, exact: 16-bit values, bytes b as 257 b, doubles as they are.
SURROGATE_AVX2_TARGET inline void loadEight(const std::uint16_t* s, __m256d* x0, __m256d* x1) {
  const __m128i v = _mm_loadu_si128(reinterpret_cast<const __m128i*>(s));
  *x0 = _mm256_cvtepi32_pd(_mm_cvtepu16_epi32(v));
  *x1 = _mm256_cvtepi32_pd(_mm_cvtepu16_epi32(_mm_srli_si128(v, 8)));
}
// Bytes I + k Step (k < 4) of v as 32-bit values 257 b = b + 256 b, each byte copied into its
// lane's two low bytes by one shuffle: fewer vector operations than widening and multiplying.
template <int I, int Step>
SURROGATE_AVX2_TARGET inline __m128i bytesTimes257(__m128i v) {
  return _mm_shuffle_epi8(v, _mm_setr_epi8(I, I, -1, -1, I + Step, I + Step, -1, -1, I + 2 * Step, I + 2 * Step, -1, -1,
                                           I + 3 * Step, I + 3 * Step, -1, -1));
}
SURROGATE_AVX2_TARGET inline void loadEight(const std::uint8_t* s, __m256d* x0, __m256d* x1) {
  const __m128i v = _mm_loadl_epi64(reinterpret_cast<const __m128i*>(s));
  *x0 = _mm256_cvtepi32_pd(bytesTimes257<0, 1>(v));
  *x1 = _mm256_cvtepi32_pd(bytesTimes257<4, 1>(v));
}
SURROGATE_AVX2_TARGET inline void loadEight(const double* s, __m256d* x0, __m256d* x1) {
  *x0 = _mm256_loadu_pd(s);
  *x1 = _mm256_loadu_pd(s + 4);
}

using lanes::channelsOfEight;
using lanes::pickBytes;
using lanes::valuesOfEight;

// Eight 32-bit integers as two vectors of four doubles, exact.
SURROGATE_AVX2_TARGET inline void asDoubles(__m256i v, __m256d* low, __m256d* high) {
  *low = _mm256_cvtepi32_pd(_mm256_castsi256_si128(v));
  *high = _mm256_cvtepi32_pd(_mm256_extracti128_si256(v, 1));
}

// R + G + B of eight interleaved RGB pixels (their 16-bit values), as doubles, exact (integer
// sums: 257 r + 257 g + 257 b for bytes).
template <typename Sample>
SURROGATE_AVX2_TARGET inline void pixelSumsOfEight(const Sample* s, __m256d* low, __m256d* high) {
  __m128i r, g, b;
  channelsOfEight(s, &r, &g, &b);
  asDoubles(_mm256_add_epi32(_mm256_add_epi32(valuesOfEight(r, s), valuesOfEight(g, s)), valuesOfEight(b, s)), low,
            high);
}

// The same for bytes, from two overlapping loads of the 24 samples: pixels 0..3 are bytes 0..11
// of the first (samples 0..15), pixels 4..7 bytes 4..15 of the second (samples 8..23).
SURROGATE_AVX2_TARGET inline void pixelSumsOfEight(const std::uint8_t* s, __m256d* low, __m256d* high) {
  const __m128i a = _mm_loadu_si128(reinterpret_cast<const __m128i*>(s));
  const __m128i b = _mm_loadu_si128(reinterpret_cast<const __m128i*>(s + 8));
  *low = _mm256_cvtepi32_pd(
      _mm_add_epi32(_mm_add_epi32(bytesTimes257<0, 3>(a), bytesTimes257<1, 3>(a)), bytesTimes257<2, 3>(a)));
  *high = _mm256_cvtepi32_pd(
      _mm_add_epi32(_mm_add_epi32(bytesTimes257<4, 3>(b), bytesTimes257<5, 3>(b)), bytesTimes257<6, 3>(b)));
}

// clamp255 on four values: compares and selects, which let NaN through as clamp255 does.
SURROGATE_AVX2_TARGET inline __m256d clamp255(__m256d v) {
  const __m256d zero = _mm256_setzero_pd(), top = _mm256_set1_pd(255.0);
  const __m256d low = _mm256_blendv_pd(v, zero, _mm256_cmp_pd(v, zero, _CMP_LT_OQ));
  return _mm256_blendv_pd(low, top, _mm256_cmp_pd(top, low, _CMP_LT_OQ));
}

// The captured luminance (kLumR R + kLumG G + kLumB B) / 257 of four pixels' channel values.
SURROGATE_AVX2_TARGET inline __m256d capturedOfFour(__m256d r, __m256d g, __m256d b) {
  const __m256d weighted = _mm256_add_pd(
      _mm256_add_pd(_mm256_mul_pd(_mm256_set1_pd(kLumR), r), _mm256_mul_pd(_mm256_set1_pd(kLumG), g)),
      _mm256_mul_pd(_mm256_set1_pd(kLumB), b));
  return _mm256_div_pd(weighted, _mm256_set1_pd(257.0));
}

// The channel values of eight interleaved pixels as doubles: r[h], g[h], b[h] hold pixels 4h..4h+3.
template <typename Sample>
SURROGATE_AVX2_TARGET inline void channelValuesOfEight(const Sample* s, __m256d r[2], __m256d g[2], __m256d b[2]) {
  __m128i sr, sg, sb;
  channelsOfEight(s, &sr, &sg, &sb);
  asDoubles(valuesOfEight(sr, s), &r[0], &r[1]);
  asDoubles(valuesOfEight(sg, s), &g[0], &g[1]);
  asDoubles(valuesOfEight(sb, s), &b[0], &b[1]);
}

// lrgbBody on eight pixels at a time, the samples parted as in rgbAvx2; the same operations on
// each value in the same order (each sum from zero, as the body's). The rest through the body.
template <typename Sample>
SURROGATE_AVX2_TARGET void lrgbAvx2(const double* cr, const double* cg, const double* cb, const double* decoded,
                                    std::size_t stride, const double* basis, const Sample* s, std::size_t pixels,
                                    double* d2) {
  __m256d bk[6];
  for (int k = 0; k < 6; ++k) bk[k] = _mm256_set1_pd(basis[k]);
  const __m256d kr = _mm256_set1_pd(kLumR), kg = _mm256_set1_pd(kLumG), kb = _mm256_set1_pd(kLumB);
  const __m256d range = _mm256_set1_pd(255.0);
  std::size_t x = 0;
  for (; x + 8 <= pixels; x += 8) {
    __m256d vr[2], vg[2], vb[2];
    channelValuesOfEight(s + 3 * x, vr, vg, vb);
    for (int h = 0; h < 2; ++h) {
      const std::size_t at = x + 4 * h;
      __m256d l = _mm256_setzero_pd();
      for (int k = 0; k < 6; ++k) l = _mm256_add_pd(l, _mm256_mul_pd(bk[k], _mm256_loadu_pd(decoded + k * stride + at)));
      const auto channel = [&](const double* c) SURROGATE_AVX2_TARGET {
        return clamp255(_mm256_div_pd(_mm256_mul_pd(_mm256_loadu_pd(c + at), l), range));
      };
      __m256d model = _mm256_setzero_pd();
      model = _mm256_add_pd(model, _mm256_mul_pd(kr, channel(cr)));
      model = _mm256_add_pd(model, _mm256_mul_pd(kg, channel(cg)));
      model = _mm256_add_pd(model, _mm256_mul_pd(kb, channel(cb)));
      const __m256d d = _mm256_sub_pd(model, capturedOfFour(vr[h], vg[h], vb[h]));
      _mm256_storeu_pd(d2 + at, _mm256_mul_pd(d, d));
    }
  }
  lrgbBody(cr + x, cg + x, cb + x, decoded + x, stride, basis, s + 3 * x, pixels - x, d2 + x);
}

// rgbBody on eight pixels at a time: the samples parted into R, G and B by byte shuffles, the
// model's 24 values by blends and permutes, then the same operations on each value in the same
// order (no fused multiply-add). The pixels past the last whole eight go through the body. The
// compiled body had gathered the interleaved values lane by lane.
template <typename Sample>
SURROGATE_AVX2_TARGET void rgbAvx2(const double* p, const Sample* s, std::size_t pixels, double* d2) {
  const __m256d kr = _mm256_set1_pd(kLumR), kg = _mm256_set1_pd(kLumG), kb = _mm256_set1_pd(kLumB);
  std::size_t x = 0;
  for (; x + 8 <= pixels; x += 8) {
    __m256d vr[2], vg[2], vb[2];
    channelValuesOfEight(s + 3 * x, vr, vg, vb);
    for (int h = 0; h < 2; ++h) {
      // Pixels 4h..4h+3: a = r0 g0 b0 r1, b = g1 b1 r2 g2, c = b2 r3 g3 b3.
      const double* q = p + 3 * (x + 4 * h);
      const __m256d a = _mm256_loadu_pd(q), b = _mm256_loadu_pd(q + 4), c = _mm256_loadu_pd(q + 8);
      const __m256d r = _mm256_permute4x64_pd(_mm256_blend_pd(_mm256_blend_pd(a, b, 0b0100), c, 0b0010),
                                              _MM_SHUFFLE(1, 2, 3, 0));  // a0 c1 b2 a3 -> a0 a3 b2 c1
      const __m256d g = _mm256_permute4x64_pd(_mm256_blend_pd(_mm256_blend_pd(a, b, 0b1001), c, 0b0100),
                                              _MM_SHUFFLE(2, 3, 0, 1));  // b0 a1 c2 b3 -> a1 b0 b3 c2
      const __m256d bl = _mm256_permute4x64_pd(_mm256_blend_pd(_mm256_blend_pd(a, b, 0b0010), c, 0b1001),
                                               _MM_SHUFFLE(3, 0, 1, 2));  // c0 b1 a2 c3 -> a2 b1 c0 c3
      const __m256d model = _mm256_add_pd(
          _mm256_add_pd(_mm256_mul_pd(kr, clamp255(r)), _mm256_mul_pd(kg, clamp255(g))), _mm256_mul_pd(kb, clamp255(bl)));
      const __m256d d = _mm256_sub_pd(model, capturedOfFour(vr[h], vg[h], vb[h]));
      _mm256_storeu_pd(d2 + x + 4 * h, _mm256_mul_pd(d, d));
    }
  }
  rgbBody(p + 3 * x, s + 3 * x, pixels - x, d2 + x);
}

// How far ahead the AVX2 accumulation and block products ask for the samples (which changes no
// value): in the pipeline the loads of dozens of streams had taken a third of their time.
constexpr std::size_t kPrefetchBytes = 256;

// accumulateBody with the sums of eight pixels in twelve registers while every photograph is
// added, then the same eight pixels' 24 samples of the mean colour in six: the same operations
// on each value in the same order. Pixels past the last whole eight go through the body.
template <typename Sample>
SURROGATE_AVX2_TARGET void accumulateAvx2(const Sample* const* images, int n, std::size_t w, std::size_t x0,
                                          std::size_t x1, const double* p, const double* weight, double* acc,
                                          double* mean, double* sum) {
  std::size_t x = x0;
  for (; x + 8 <= x1; x += 8) {
    __m256d a[6][2];
    for (int k = 0; k < 6; ++k) {
      a[k][0] = _mm256_loadu_pd(acc + k * w + x);
      a[k][1] = _mm256_loadu_pd(acc + k * w + x + 4);
    }
    for (int i = 0; i < n; ++i) {
      __m256d s0, s1;
      _mm_prefetch(reinterpret_cast<const char*>(images[i] + 3 * x) + kPrefetchBytes, _MM_HINT_T0);
      pixelSumsOfEight(images[i] + 3 * x, &s0, &s1);
      for (int k = 0; k < 6; ++k) {
        const __m256d pk = _mm256_broadcast_sd(p + static_cast<std::size_t>(k) * n + i);
        a[k][0] = _mm256_add_pd(a[k][0], _mm256_mul_pd(pk, s0));
        a[k][1] = _mm256_add_pd(a[k][1], _mm256_mul_pd(pk, s1));
      }
    }
    for (int k = 0; k < 6; ++k) {
      _mm256_storeu_pd(acc + k * w + x, a[k][0]);
      _mm256_storeu_pd(acc + k * w + x + 4, a[k][1]);
    }
    double* m = mean + 3 * x;
    __m256d mv[6];
    for (int u = 0; u < 6; ++u) mv[u] = _mm256_loadu_pd(m + 4 * u);
    for (int i = 0; i < n; ++i) {
      const double wi = weight[i];
      if (wi == 0) continue;
      const __m256d wv = _mm256_set1_pd(wi);
      __m256d v[6];
      for (int u = 0; u < 3; ++u) loadEight(images[i] + 3 * x + 8 * u, &v[2 * u], &v[2 * u + 1]);
      for (int u = 0; u < 6; ++u) mv[u] = _mm256_add_pd(mv[u], _mm256_mul_pd(wv, v[u]));
    }
    for (int u = 0; u < 6; ++u) _mm256_storeu_pd(m + 4 * u, mv[u]);
  }
  accumulateBody(images, n, w, x, x1, p, weight, acc, mean, sum);
}

// The first element of a equal to zero (there is one: the extreme found was zero).
inline double firstZero(const double* a, std::size_t count) {
  std::size_t x = 0;
  while (a[x] != 0.0 && x + 1 < count) ++x;
  return a[x];
}

// rangeOf (row_kernels.h): per lane, min_pd(v, m) is v < m ? v : m and max_pd(v, m) is
// v > m ? v : m, the standard algorithms' own steps; NaN anywhere sends the row to them.
SURROGATE_AVX2_TARGET void rangeAvx2(const double* a, std::size_t count, double* lo, double* hi) {
  __m256d mn0 = _mm256_set1_pd(a[0]), mn1 = mn0, mx0 = mn0, mx1 = mn0;
  __m256d unordered = _mm256_setzero_pd();
  std::size_t x = 0;
  for (; x + 8 <= count; x += 8) {
    const __m256d v0 = _mm256_loadu_pd(a + x), v1 = _mm256_loadu_pd(a + x + 4);
    mn0 = _mm256_min_pd(v0, mn0);
    mn1 = _mm256_min_pd(v1, mn1);
    mx0 = _mm256_max_pd(v0, mx0);
    mx1 = _mm256_max_pd(v1, mx1);
    unordered = _mm256_or_pd(unordered, _mm256_cmp_pd(v0, v1, _CMP_UNORD_Q));
  }
  alignas(32) double low[4], high[4];
  _mm256_store_pd(low, _mm256_min_pd(mn0, mn1));
  _mm256_store_pd(high, _mm256_max_pd(mx0, mx1));
  bool nan = _mm256_movemask_pd(unordered) != 0;
  double l = low[0], h = high[0];
  for (int u = 1; u < 4; ++u) {
    l = low[u] < l ? low[u] : l;
    h = high[u] > h ? high[u] : h;
  }
  for (; x < count; ++x) {
    nan = nan || a[x] != a[x];
    l = a[x] < l ? a[x] : l;
    h = a[x] > h ? a[x] : h;
  }
  if (nan) {
    *lo = *std::min_element(a, a + count);
    *hi = *std::max_element(a, a + count);
    return;
  }
  *lo = l == 0.0 ? firstZero(a, count) : l;
  *hi = h == 0.0 ? firstZero(a, count) : h;
}

// detail::roundClamped(v, 255) (fit/quantise.h) on four values, as integers.
SURROGATE_AVX2_TARGET inline __m128i roundClamped255(__m256d v) {
  return _mm256_cvttpd_epi32(lanes::roundClampedFour(v, _mm256_set1_pd(255.0)));
}

// The quantisers sixteen coefficients at a time (the compiled body had spilled registers):
// `value` gives toByte's argument for four; the bytes (0..255) pass the saturating packs. The
// decoding follows in a loop of its own, which ran faster than inside this one.
template <typename Value>
SURROGATE_AVX2_TARGET inline std::size_t quantiseSixteen(const double* a, std::size_t count, Value value,
                                                         std::uint8_t* bytes) {
  std::size_t j = 0;
  for (; j + 16 <= count; j += 16) {
    __m128i q[4];
    for (int u = 0; u < 4; ++u) q[u] = roundClamped255(value(_mm256_loadu_pd(a + j + 4 * u)));
    const __m128i packed = _mm_packus_epi16(_mm_packs_epi32(q[0], q[1]), _mm_packs_epi32(q[2], q[3]));
    _mm_storeu_si128(reinterpret_cast<__m128i*>(bytes + j), packed);
  }
  return j;
}

// PTM: byte = toByte(a / scale + bias), decoded (byte - bias) * scale (integers, then one
// product), as PtmQuantisation does.
SURROGATE_AVX2_TARGET void ptmAvx2(const double* a, std::size_t count, const PtmQuantisation& q, std::uint8_t* bytes,
                                   double* decoded) {
  const __m256d scale = _mm256_set1_pd(q.scale), bias = _mm256_set1_pd(static_cast<double>(q.bias));
  const __m128i biasInt = _mm_set1_epi32(q.bias);
  const std::size_t done = quantiseSixteen(
      a, count, [&](__m256d v) SURROGATE_AVX2_TARGET { return _mm256_add_pd(_mm256_div_pd(v, scale), bias); },
      bytes);
  for (std::size_t j = 0; j < done; j += 16) {
    __m128i b = _mm_loadu_si128(reinterpret_cast<const __m128i*>(bytes + j));
    for (int u = 0; u < 4; ++u, b = _mm_srli_si128(b, 4))
      _mm256_storeu_pd(decoded + j + 4 * u,
                       _mm256_mul_pd(_mm256_cvtepi32_pd(_mm_sub_epi32(_mm_cvtepu8_epi32(b), biasInt)), scale));
  }
  quantiseBody(a + done, count - done, q, bytes + done, decoded + done);
}

// HSH: byte = toByte((a - bias) / scale * 255); the decoding's division by 255 once per byte
// value, by q.decode itself into a table, not once per coefficient.
SURROGATE_AVX2_TARGET void hshAvx2(const double* a, std::size_t count, const HshQuantisation& q, std::uint8_t* bytes,
                                   double* decoded) {
  if (q.scale == 0) return quantiseBody(a, count, q, bytes, decoded);
  const __m256d scale = _mm256_set1_pd(static_cast<double>(q.scale));
  const __m256d bias = _mm256_set1_pd(static_cast<double>(q.bias)), range = _mm256_set1_pd(255.0);
  const auto value = [&](__m256d v) SURROGATE_AVX2_TARGET {
    return _mm256_mul_pd(_mm256_div_pd(_mm256_sub_pd(v, bias), scale), range);
  };
  const std::size_t done = quantiseSixteen(a, count, value, bytes);
  for (std::size_t j = done; j < count; ++j) bytes[j] = q.quantise(a[j]);
  double table[256];
  for (int b = 0; b < 256; ++b) table[b] = q.decode(static_cast<std::uint8_t>(b));
  for (std::size_t j = 0; j < count; ++j) decoded[j] = table[bytes[j]];
}

// G rows of m (G <= kMaxRows) over a whole block, eight samples at a time: 2G accumulators
// (with the samples and a factor, 15 of 16 registers) while the columns are run through once.
constexpr int kMaxRows = 6;
template <int G, typename Sample>
SURROGATE_AVX2_TARGET inline void multiplyRowsAvx2(const double* m, int cols, const Sample* const* src,
                                                   std::size_t offset, double* out, std::size_t outStride) {
  for (std::size_t j = 0; j < kProductBlock; j += 8) {
    __m256d a[G][2];
    for (int q = 0; q < G; ++q) a[q][0] = a[q][1] = _mm256_setzero_pd();
    for (int c = 0; c < cols; ++c) {
      __m256d x0, x1;
      _mm_prefetch(reinterpret_cast<const char*>(src[c] + offset + j) + kPrefetchBytes, _MM_HINT_T0);
      loadEight(src[c] + offset + j, &x0, &x1);
      for (int q = 0; q < G; ++q) {
        const __m256d mq = _mm256_broadcast_sd(m + static_cast<std::size_t>(q) * cols + c);
        a[q][0] = _mm256_add_pd(a[q][0], _mm256_mul_pd(mq, x0));
        a[q][1] = _mm256_add_pd(a[q][1], _mm256_mul_pd(mq, x1));
      }
    }
    for (int q = 0; q < G; ++q) {
      _mm256_storeu_pd(out + q * outStride + j, _mm256_add_pd(_mm256_setzero_pd(), a[q][0]));
      _mm256_storeu_pd(out + q * outStride + j + 4, _mm256_add_pd(_mm256_setzero_pd(), a[q][1]));
    }
  }
}

template <typename Sample>
SURROGATE_AVX2_TARGET void multiplyAvx2(const double* m, int rows, int cols, const Sample* const* src,
                                        std::size_t offset, double* out, std::size_t outStride) {
  // Few groups of near equal sizes: HSH's 9 rows as 5 + 4 (one row alone waits on the adds).
  const int groups = (rows + kMaxRows - 1) / kMaxRows;
  for (int g = 0, r = 0; g < groups; ++g) {
    const int size = rows / groups + (g < rows % groups ? 1 : 0);
    const double* mr = m + static_cast<std::size_t>(r) * cols;
    double* o = out + r * outStride;
    switch (size) {
      case 6: multiplyRowsAvx2<6>(mr, cols, src, offset, o, outStride); break;
      case 5: multiplyRowsAvx2<5>(mr, cols, src, offset, o, outStride); break;
      case 4: multiplyRowsAvx2<4>(mr, cols, src, offset, o, outStride); break;
      case 3: multiplyRowsAvx2<3>(mr, cols, src, offset, o, outStride); break;
      case 2: multiplyRowsAvx2<2>(mr, cols, src, offset, o, outStride); break;
      default: multiplyRowsAvx2<1>(mr, cols, src, offset, o, outStride); break;
    }
    r += size;
  }
}
#else
void ptmAvx2(const double* a, std::size_t count, const PtmQuantisation& q, std::uint8_t* bytes, double* decoded) {
  quantiseBody(a, count, q, bytes, decoded);
}
void hshAvx2(const double* a, std::size_t count, const HshQuantisation& q, std::uint8_t* bytes, double* decoded) {
  quantiseBody(a, count, q, bytes, decoded);
}
void rangeAvx2(const double* a, std::size_t count, double* lo, double* hi) {
  *lo = *std::min_element(a, a + count);
  *hi = *std::max_element(a, a + count);
}
template <typename Sample>
void lrgbAvx2(const double* cr, const double* cg, const double* cb, const double* decoded, std::size_t stride,
              const double* basis, const Sample* s, std::size_t pixels, double* d2) {
  lrgbBody(cr, cg, cb, decoded, stride, basis, s, pixels, d2);
}
template <typename Sample>
void rgbAvx2(const double* p, const Sample* s, std::size_t pixels, double* d2) {
  rgbBody(p, s, pixels, d2);
}
template <typename Sample>
void accumulateAvx2(const Sample* const* images, int n, std::size_t w, std::size_t x0, std::size_t x1,
                    const double* p, const double* weight, double* acc, double* mean, double* sum) {
  accumulateBody(images, n, w, x0, x1, p, weight, acc, mean, sum);
}
template <typename Sample>
void multiplyAvx2(const double* m, int rows, int cols, const Sample* const* src, std::size_t offset, double* out,
                  std::size_t outStride) {
  multiplyBody(m, rows, cols, src, offset, out, outStride);
}
#endif

// The public functions' bodies, for either kind of sample.
template <typename Sample>
void accumulateLrgbOf(const Sample* const* images, int n, std::size_t w, std::size_t x0, std::size_t x1,
                      const double* p, const double* weight, double* acc, double* mean, double* sum, KernelIsa isa) {
  if (isa == KernelIsa::Avx2) return accumulateAvx2(images, n, w, x0, x1, p, weight, acc, mean, sum);
  accumulateBody(images, n, w, x0, x1, p, weight, acc, mean, sum);
}

template <typename Sample>
void squaredErrorsLrgbOf(const double* cr, const double* cg, const double* cb, const double* decoded,
                         std::size_t stride, const double* basis, const Sample* s, std::size_t pixels, double* d2,
                         KernelIsa isa) {
  if (isa == KernelIsa::Avx2) return lrgbAvx2(cr, cg, cb, decoded, stride, basis, s, pixels, d2);
  lrgbBody(cr, cg, cb, decoded, stride, basis, s, pixels, d2);
}

template <typename Sample>
void squaredErrorsRgbOf(const double* rendered, const Sample* s, std::size_t pixels, double* d2, KernelIsa isa) {
  if (isa == KernelIsa::Avx2) return rgbAvx2(rendered, s, pixels, d2);
  rgbBody(rendered, s, pixels, d2);
}

template <typename Sample>
void multiplyBlockOf(const double* m, int rows, int cols, const Sample* const* src, std::size_t offset, double* out,
                     std::size_t outStride, KernelIsa isa) {
  if (isa == KernelIsa::Avx2) return multiplyAvx2(m, rows, cols, src, offset, out, outStride);
  multiplyBody(m, rows, cols, src, offset, out, outStride);
}

}  // namespace

KernelIsa activeKernelIsa() { return lanes::kAvx2Compiled && cpuHasAvx2() ? KernelIsa::Avx2 : KernelIsa::Baseline; }

void accumulateLrgb(const std::uint16_t* const* images, int n, std::size_t w, std::size_t x0, std::size_t x1,
                    const double* p, const double* weight, double* acc, double* mean, double* sum, KernelIsa isa) {
  accumulateLrgbOf(images, n, w, x0, x1, p, weight, acc, mean, sum, isa);
}
void accumulateLrgb(const std::uint8_t* const* images, int n, std::size_t w, std::size_t x0, std::size_t x1,
                    const double* p, const double* weight, double* acc, double* mean, double* sum, KernelIsa isa) {
  accumulateLrgbOf(images, n, w, x0, x1, p, weight, acc, mean, sum, isa);
}

void squaredErrorsLrgb(const double* cr, const double* cg, const double* cb, const double* decoded,
                       std::size_t stride, const double* basis, const std::uint16_t* s, std::size_t pixels,
                       double* d2, KernelIsa isa) {
  squaredErrorsLrgbOf(cr, cg, cb, decoded, stride, basis, s, pixels, d2, isa);
}
void squaredErrorsLrgb(const double* cr, const double* cg, const double* cb, const double* decoded,
                       std::size_t stride, const double* basis, const std::uint8_t* s, std::size_t pixels,
                       double* d2, KernelIsa isa) {
  squaredErrorsLrgbOf(cr, cg, cb, decoded, stride, basis, s, pixels, d2, isa);
}

void squaredErrorsRgb(const double* rendered, const std::uint16_t* s, std::size_t pixels, double* d2,
                      KernelIsa isa) {
  squaredErrorsRgbOf(rendered, s, pixels, d2, isa);
}
void squaredErrorsRgb(const double* rendered, const std::uint8_t* s, std::size_t pixels, double* d2,
                      KernelIsa isa) {
  squaredErrorsRgbOf(rendered, s, pixels, d2, isa);
}

void rangeOf(const double* a, std::size_t count, double* lo, double* hi, KernelIsa isa) {
  if (isa == KernelIsa::Avx2) return rangeAvx2(a, count, lo, hi);
  *lo = *std::min_element(a, a + count);
  *hi = *std::max_element(a, a + count);
}

void quantisePtm(const double* a, std::size_t count, const PtmQuantisation& q, std::uint8_t* bytes, double* decoded,
                 KernelIsa isa) {
  if (isa == KernelIsa::Avx2) return ptmAvx2(a, count, q, bytes, decoded);
  quantiseBody(a, count, q, bytes, decoded);
}

void quantiseHsh(const double* a, std::size_t count, const HshQuantisation& q, std::uint8_t* bytes, double* decoded,
                 KernelIsa isa) {
  if (isa == KernelIsa::Avx2) return hshAvx2(a, count, q, bytes, decoded);
  quantiseBody(a, count, q, bytes, decoded);
}

void multiplyBlock(const double* m, int rows, int cols, const std::uint16_t* const* src, std::size_t offset,
                   double* out, std::size_t outStride, KernelIsa isa) {
  multiplyBlockOf(m, rows, cols, src, offset, out, outStride, isa);
}
void multiplyBlock(const double* m, int rows, int cols, const std::uint8_t* const* src, std::size_t offset,
                   double* out, std::size_t outStride, KernelIsa isa) {
  multiplyBlockOf(m, rows, cols, src, offset, out, outStride, isa);
}
void multiplyBlock(const double* m, int rows, int cols, const double* const* src, std::size_t offset,
                   double* out, std::size_t outStride, KernelIsa isa) {
  multiplyBlockOf(m, rows, cols, src, offset, out, outStride, isa);
}

}  // namespace surrogate::fit
