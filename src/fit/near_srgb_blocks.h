// Private to src/fit (near_fit.cpp): the per-block sRGB fall-off of the near fit's kernels
// (fit/near_fit.h), four values at once: GCC's vector extension (every machine) and, where
// cpuHasAvx2() (row_kernels.h's activeKernelIsa), AVX2: f^(1/2.4) from its table, 8-bit samples
// read four pixels at a time and scaled (the toe's tables included), the model's values
// unscaled, and the errors' luminances. Each lane does the operations of the scalar functions
// of srgb_falloff.h (and of near_fit.cpp's error loops) in their order (sqrt, the tables'
// interpolation, the multiply-add above the toe; no fused multiply-add), so every variant gives
// the scalar functions' bits; a lane past a table (the formula's case) is done by the scalar
// functions. (Done one value at a time, these took most of the near fits' time.)
#pragma once

#include <cstdint>
#include <cstring>

#include "fit/row_kernels.h"
#include "fit/srgb_falloff.h"

#if defined(__x86_64__) && defined(__GNUC__)
#include <immintrin.h>
#define SURROGATE_NEAR_SRGB_AVX2 1
#define SURROGATE_NEAR_AVX2_BLOCK __attribute__((target("avx2"), noinline))
#define SURROGATE_NEAR_AVX2_INLINE __attribute__((target("avx2"), always_inline)) inline
#else
#define SURROGATE_NEAR_SRGB_AVX2 0
#endif

namespace surrogate::fit::falloff {

// Four values at once: GCC's vector extension, each lane rounded as a double (no fused
// multiply-add: -ffp-contract=off and no "fma" target), so a lane's value does not depend on
// its neighbours or on the instruction set.
typedef double V __attribute__((vector_size(32), aligned(8)));
constexpr int kLanes = 4;
#define NEAR_LOAD(v, p) __builtin_memcpy(&(v), (p), sizeof(V))
#define NEAR_STORE(p, v) __builtin_memcpy((p), &(v), sizeof(V))

// o[b] = scaledWith(sample b, fi[b], pi[b]) for the samples s[3 b] (one channel of a row),
// four at a time above the toe, one at a time where a lane is in the toe.
template <typename Sample>
SURROGATE_FALLOFF_INLINE void scaleSrgb(const double* decode16, const double* encode, const Sample* s,
                                        const double* fi, const double* pi, double* o, int len) {
  int b = 0;
  for (; b + kLanes <= len; b += kLanes) {
    const V v = V{static_cast<double>(sampleValue(s[3 * b])), static_cast<double>(sampleValue(s[3 * b + 3])),
                  static_cast<double>(sampleValue(s[3 * b + 6])), static_cast<double>(sampleValue(s[3 * b + 9]))} *
                (1.0 / 65535.0);
    V p;
    NEAR_LOAD(p, pi + b);
    const V y = (v + 0.055) * p - 0.055;
    const auto above = (v > kToe) & (y > kToe);
    if (above[0] & above[1] & above[2] & above[3]) {
      const V r = y * 65535.0;
      NEAR_STORE(o + b, r);
    } else {
      for (int j = b; j < b + kLanes; ++j) o[j] = scaledWith(decode16, encode, sampleValue(s[3 * j]), fi[j], pi[j]);
    }
  }
  for (; b < len; ++b) o[b] = scaledWith(decode16, encode, sampleValue(s[3 * b]), fi[b], pi[b]);
}

// m[b] = unscaledWith(m[b], gi[b], gp[b]) in place, four at a time above the toe, one at a
// time where a lane is in the toe.
SURROGATE_FALLOFF_INLINE void unscaleSrgb(const double* decode, const double* encode, double* m, const double* gi,
                                          const double* gp, int len) {
  int b = 0;
  for (; b + kLanes <= len; b += kLanes) {
    V v, p;
    NEAR_LOAD(v, m + b);
    NEAR_LOAD(p, gp + b);
    v = v * (1.0 / 255.0);
    const V y = (v + 0.055) * p - 0.055;
    const auto above = (v > kToe) & (y > kToe);
    if (above[0] & above[1] & above[2] & above[3]) {
      const V r = 255.0 * y;
      NEAR_STORE(m + b, r);
    } else {
      for (int j = b; j < b + kLanes; ++j) m[j] = unscaledWith(decode, encode, m[j], gi[j], gp[j]);
    }
  }
  for (; b < len; ++b) m[b] = unscaledWith(decode, encode, m[b], gi[b], gp[b]);
}

#if SURROGATE_NEAR_SRGB_AVX2

// interpolated(pairs, range, x) lane by lane, x in [0, range): each lane's pair read at once
// (16 bytes), the four pairs transposed into the values and the differences.
SURROGATE_NEAR_AVX2_INLINE __m256d interpolatedAvx2(const double* pairs, double range, __m256d x) {
  const __m256d at = _mm256_mul_pd(x, _mm256_set1_pd(kTable / range));
  const __m128i j = _mm256_cvttpd_epi32(at);  // static_cast<int>, at >= 0
  const __m256d u = _mm256_sub_pd(at, _mm256_cvtepi32_pd(j));
  const double* p0 = pairs + 2 * _mm_cvtsi128_si32(j);
  const double* p1 = pairs + 2 * _mm_extract_epi32(j, 1);
  const double* p2 = pairs + 2 * _mm_extract_epi32(j, 2);
  const double* p3 = pairs + 2 * _mm_extract_epi32(j, 3);
  const __m256d even = _mm256_insertf128_pd(_mm256_castpd128_pd256(_mm_loadu_pd(p0)), _mm_loadu_pd(p2), 1);
  const __m256d odd = _mm256_insertf128_pd(_mm256_castpd128_pd256(_mm_loadu_pd(p1)), _mm_loadu_pd(p3), 1);
  // (f0 f1 f2 f3) and (d0 d1 d2 d3): even = (f0 d0 | f2 d2), odd = (f1 d1 | f3 d3).
  return _mm256_add_pd(_mm256_unpacklo_pd(even, odd), _mm256_mul_pd(u, _mm256_unpackhi_pd(even, odd)));
}

// rootWith(table, f[b .. b + 3]) into fp[b .. b + 3], returned: on the table where all four are
// in its range, else one at a time.
SURROGATE_NEAR_AVX2_INLINE __m256d rootsOfFour(const double* table, const double* f, double* fp, int b) {
  const __m256d v = _mm256_loadu_pd(f + b);
  const __m256d inside = _mm256_and_pd(_mm256_cmp_pd(v, _mm256_setzero_pd(), _CMP_GE_OQ),
                                       _mm256_cmp_pd(v, _mm256_set1_pd(kRootRangeU * kRootRangeU), _CMP_LT_OQ));
  if (_mm256_movemask_pd(inside) != 0xF) {
    for (int j = b; j < b + 4; ++j) fp[j] = rootWith(table, f[j]);
    return _mm256_loadu_pd(fp + b);
  }
  const __m256d r = interpolatedAvx2(table, kRootRangeU, _mm256_sqrt_pd(v));
  _mm256_storeu_pd(fp + b, r);
  return r;
}

// fp[b] = rootWith(table, f[b]), b < len.
SURROGATE_NEAR_AVX2_BLOCK inline void rootsAvx2(const double* table, const double* f, double* fp, int len) {
  int b = 0;
  for (; b + 4 <= len; b += 4) rootsOfFour(table, f, fp, b);
  for (; b < len; ++b) fp[b] = rootWith(table, f[b]);
}

// The bytes of four interleaved 8-bit RGB pixels at s as three lanes of four doubles, channel
// by channel: exactly twelve bytes read (a row may end there). fit/row_kernels.cpp's
// channelsOfEight does the same for eight pixels into 16-bit lanes.
SURROGATE_NEAR_AVX2_INLINE void channelsOfFour(const std::uint8_t* s, __m256d out[3]) {
  const __m128i pick[3] = {_mm_setr_epi8(0, -1, -1, -1, 3, -1, -1, -1, 6, -1, -1, -1, 9, -1, -1, -1),
                           _mm_setr_epi8(1, -1, -1, -1, 4, -1, -1, -1, 7, -1, -1, -1, 10, -1, -1, -1),
                           _mm_setr_epi8(2, -1, -1, -1, 5, -1, -1, -1, 8, -1, -1, -1, 11, -1, -1, -1)};
  std::uint64_t low;
  std::uint32_t high;
  std::memcpy(&low, s, sizeof low);
  std::memcpy(&high, s + 8, sizeof high);
  const __m128i bytes = _mm_insert_epi32(_mm_cvtsi64_si128(static_cast<long long>(low)), static_cast<int>(high), 2);
  for (int ch = 0; ch < 3; ++ch) out[ch] = _mm256_cvtepi32_pd(_mm_shuffle_epi8(bytes, pick[ch]));
}

// The lanes j of pixels b .. b + 3 of channel ch (o: its plane) not set in `above` (in the toe):
// 65535 encodeLinear(decode16[value] f), in linear light, as scaledWith.
SURROGATE_NEAR_AVX2_BLOCK inline void scaleToe(const double* decode16, const double* encode, const std::uint8_t* s,
                                               const double* fi, const double* pi, double* o, int ch, int b,
                                               int above) {
  const __m256d l = _mm256_mul_pd(
      _mm256_setr_pd(decode16[sampleValue(s[3 * b + ch])], decode16[sampleValue(s[3 * b + 3 + ch])],
                     decode16[sampleValue(s[3 * b + 6 + ch])], decode16[sampleValue(s[3 * b + 9 + ch])]),
      _mm256_loadu_pd(fi + b));
  const __m256d inside =
      _mm256_and_pd(_mm256_cmp_pd(l, _mm256_setzero_pd(), _CMP_GE_OQ), _mm256_cmp_pd(l, _mm256_set1_pd(8.0), _CMP_LT_OQ));
  // A lane past the table reads it at 0, and is then done by the formula (scaledWith).
  double slow[4];
  _mm256_storeu_pd(slow, _mm256_mul_pd(_mm256_set1_pd(65535.0),
                                       interpolatedAvx2(encode, kEncodeRangeU, _mm256_sqrt_pd(_mm256_and_pd(l, inside)))));
  const int tabled = _mm256_movemask_pd(inside);
  for (int j = 0; j < 4; ++j)
    if (!(above >> j & 1))
      o[b + j] = tabled >> j & 1 ? slow[j] : scaledWith(decode16, encode, sampleValue(s[3 * (b + j) + ch]), fi[b + j], pi[b + j]);
}

// out[ch][b] = scaledWith(the 16-bit value of channel ch of pixel b, fi[b], pi[b]) for the
// interleaved 8-bit RGB row s, b < len, with pi[b] = rootWith(root, fi[b]) made here first (one
// call a light and block rather than two: the near fits make a call for every 32 pixels).
SURROGATE_NEAR_AVX2_BLOCK inline void scaleSrgbAvx2(const double* decode16, const double* encode, const double* root,
                                                    const std::uint8_t* s, const double* fi, double* pi,
                                                    double* const* out, int len) {
  const __m256d toe = _mm256_set1_pd(kToe), offset = _mm256_set1_pd(0.055);
  // The row's next block (the caller's next call for this photograph): dozens of photographs'
  // rows are more streams than the hardware prefetcher follows.
  for (int ahead = 0; ahead < 3 * len; ahead += 64) __builtin_prefetch(s + 3 * len + ahead);
  int b = 0;
  for (; b + 4 <= len; b += 4) rootsOfFour(root, fi, pi, b);
  for (; b < len; ++b) pi[b] = rootWith(root, fi[b]);
  for (b = 0; b + 4 <= len; b += 4) {
    __m256d channel[3];
    channelsOfFour(s + 3 * b, channel);
    const __m256d p = _mm256_loadu_pd(pi + b);
    __m256d fast[3], above[3];
    for (int ch = 0; ch < 3; ++ch) {
      // sampleValue(byte) = 257 byte, exact as a double either way; then v = value / 65535.
      const __m256d v =
          _mm256_mul_pd(_mm256_mul_pd(channel[ch], _mm256_set1_pd(257.0)), _mm256_set1_pd(1.0 / 65535.0));
      const __m256d y = _mm256_sub_pd(_mm256_mul_pd(_mm256_add_pd(v, offset), p), offset);
      above[ch] = _mm256_and_pd(_mm256_cmp_pd(v, toe, _CMP_GT_OQ), _mm256_cmp_pd(y, toe, _CMP_GT_OQ));
      fast[ch] = _mm256_mul_pd(y, _mm256_set1_pd(65535.0));
      _mm256_storeu_pd(out[ch] + b, fast[ch]);
    }
    // One test for the three channels: the toe is rare in most photographs.
    if (_mm256_movemask_pd(_mm256_and_pd(_mm256_and_pd(above[0], above[1]), above[2])) == 0xF) continue;
    for (int ch = 0; ch < 3; ++ch) {
      const int bits = _mm256_movemask_pd(above[ch]);
      if (bits != 0xF) scaleToe(decode16, encode, s, fi, pi, out[ch], ch, b, bits);
    }
  }
  for (; b < len; ++b)
    for (int ch = 0; ch < 3; ++ch) out[ch][b] = scaledWith(decode16, encode, sampleValue(s[3 * b + ch]), fi[b], pi[b]);
}

// unscaledWith(m, g, p) of four values m above the toe, with p the root of g: 255 ((v + 0.055) p
// - 0.055) for v = m / 255; *above is set in the lanes where v and that value both lie above the
// toe (the others are unscaleFour's, on the tables).
SURROGATE_NEAR_AVX2_INLINE __m256d unscaleAboveToe(__m256d m, __m256d p, __m256d* above) {
  const __m256d toe = _mm256_set1_pd(kToe), offset = _mm256_set1_pd(0.055);
  const __m256d v = _mm256_mul_pd(m, _mm256_set1_pd(1.0 / 255.0));
  const __m256d y = _mm256_sub_pd(_mm256_mul_pd(_mm256_add_pd(v, offset), p), offset);
  *above = _mm256_and_pd(_mm256_cmp_pd(v, toe, _CMP_GT_OQ), _mm256_cmp_pd(y, toe, _CMP_GT_OQ));
  return _mm256_mul_pd(_mm256_set1_pd(255.0), y);
}

// unscaledWith(m, gi[b + j], gp[b + j]) for the four values m of lanes j.
SURROGATE_NEAR_AVX2_INLINE __m256d unscaleFour(const double* decode, const double* encode, __m256d m, const double* gi,
                                               const double* gp, int b) {
  __m256d above;
  const __m256d fast = unscaleAboveToe(m, _mm256_loadu_pd(gp + b), &above);
  if (_mm256_movemask_pd(above) == 0xF) return fast;
  const __m256d v = _mm256_mul_pd(m, _mm256_set1_pd(1.0 / 255.0));
  // Lanes in the toe: 255 encodeLinear(decodeEncoded(v) g), both on their tables unless past them.
  const __m256d zero = _mm256_setzero_pd();
  const __m256d encoded =
      _mm256_and_pd(_mm256_cmp_pd(v, zero, _CMP_GE_OQ), _mm256_cmp_pd(v, _mm256_set1_pd(kDecodeRange), _CMP_LT_OQ));
  const __m256d l =
      _mm256_mul_pd(interpolatedAvx2(decode, kDecodeRange, _mm256_and_pd(v, encoded)), _mm256_loadu_pd(gi + b));
  const __m256d inside = _mm256_and_pd(
      encoded, _mm256_and_pd(_mm256_cmp_pd(l, zero, _CMP_GE_OQ), _mm256_cmp_pd(l, _mm256_set1_pd(8.0), _CMP_LT_OQ)));
  // A lane past a table reads it at 0, and is then done by the formulas (unscaledWith).
  const __m256d slow = _mm256_mul_pd(_mm256_set1_pd(255.0),
                                     interpolatedAvx2(encode, kEncodeRangeU, _mm256_sqrt_pd(_mm256_and_pd(l, inside))));
  const int done = _mm256_movemask_pd(_mm256_or_pd(above, inside));
  if (done == 0xF) return _mm256_blendv_pd(slow, fast, above);
  double given[4], out[4];
  _mm256_storeu_pd(given, m);
  _mm256_storeu_pd(out, _mm256_blendv_pd(slow, fast, above));
  for (int j = 0; j < 4; ++j)
    if (!(done >> j & 1)) out[j] = unscaledWith(decode, encode, given[j], gi[b + j], gp[b + j]);
  return _mm256_loadu_pd(out);
}

// m[b] = unscaledWith(m[b], gi[b], gp[b]) in place, b < len.
SURROGATE_NEAR_AVX2_BLOCK inline void unscaleSrgbAvx2(const double* decode, const double* encode, double* m,
                                                      const double* gi, const double* gp, int len) {
  int b = 0;
  for (; b + 4 <= len; b += 4) _mm256_storeu_pd(m + b, unscaleFour(decode, encode, _mm256_loadu_pd(m + b), gi, gp, b));
  for (; b < len; ++b) m[b] = unscaledWith(decode, encode, m[b], gi[b], gp[b]);
}

// std::clamp(v, 0, 255) lane by lane, as near_fit.cpp's clamp255.
SURROGATE_NEAR_AVX2_INLINE __m256d clamp(__m256d v) {
  const __m256d zero = _mm256_setzero_pd(), top = _mm256_set1_pd(255.0);
  const __m256d low = _mm256_blendv_pd(v, zero, _mm256_cmp_pd(v, zero, _CMP_LT_OQ));
  return _mm256_blendv_pd(low, top, _mm256_cmp_pd(top, low, _CMP_LT_OQ));
}

// (model - captured)^2 for four pixels: model = the Rec. 709 luminance of the clamped channels
// r0, r1, r2; captured = that of the 8-bit RGB pixels at s in 0..255 units.
SURROGATE_NEAR_AVX2_INLINE __m256d luminanceErrorsOfFour(__m256d r0, __m256d r1, __m256d r2, const std::uint8_t* s) {
  __m256d value[3];  // sampleValue: 257 byte, exact
  channelsOfFour(s, value);
  for (int ch = 0; ch < 3; ++ch) value[ch] = _mm256_mul_pd(value[ch], _mm256_set1_pd(257.0));
  const __m256d model =
      _mm256_add_pd(_mm256_add_pd(_mm256_mul_pd(_mm256_set1_pd(kLumR), clamp(r0)),
                                  _mm256_mul_pd(_mm256_set1_pd(kLumG), clamp(r1))),
                    _mm256_mul_pd(_mm256_set1_pd(kLumB), clamp(r2)));
  const __m256d captured = _mm256_mul_pd(
      _mm256_add_pd(_mm256_add_pd(_mm256_mul_pd(_mm256_set1_pd(kLumR), value[0]),
                                  _mm256_mul_pd(_mm256_set1_pd(kLumG), value[1])),
                    _mm256_mul_pd(_mm256_set1_pd(kLumB), value[2])),
      _mm256_set1_pd(1.0 / 257.0));
  const __m256d d = _mm256_sub_pd(model, captured);
  return _mm256_mul_pd(d, d);
}

// The same for one pixel b.
SURROGATE_FALLOFF_INLINE double luminanceErrorOfOne(double r0, double r1, double r2, const std::uint8_t* s, int b) {
  auto one = [](double v) { const double l = v < 0.0 ? 0.0 : v; return 255.0 < l ? 255.0 : l; };
  const double model = kLumR * one(r0) + kLumG * one(r1) + kLumB * one(r2);
  const double captured =
      (kLumR * sampleValue(s[3 * b]) + kLumG * sampleValue(s[3 * b + 1]) + kLumB * sampleValue(s[3 * b + 2])) *
      (1.0 / 257.0);
  return (model - captured) * (model - captured);
}

// d2[b] = (model - captured)^2, b < len, for the errors of sRGB samples (near_fit.cpp's
// channelErrors and lrgbErrors): each of the model's channels unscaled (unscaledWith, as
// unscaleSrgbAvx2), then as luminanceErrorsOfFour, four pixels at a time without planes between
// the steps. The model's channels are m[ch] (lum null: channelErrors) or m[ch] times lum / 255
// (lrgbErrors).
// gp[b] = rootWith(root, gi[b]) is made first, as scaleSrgbAvx2 makes its roots.
SURROGATE_NEAR_AVX2_BLOCK inline void unscaledErrorsAvx2(const double* decode, const double* encode, const double* root,
                                                         const double* const* m, const double* lum, const double* gi,
                                                         double* gp, const std::uint8_t* s, double* d2, int len) {
  for (int ahead = 0; ahead < 3 * len; ahead += 64) __builtin_prefetch(s + 3 * len + ahead);
  int b = 0;
  for (; b + 4 <= len; b += 4) rootsOfFour(root, gi, gp, b);
  for (; b < len; ++b) gp[b] = rootWith(root, gi[b]);
  for (b = 0; b + 4 <= len; b += 4) {
    __m256d given[3], r[3], above[3];
    const __m256d l = lum ? _mm256_mul_pd(_mm256_loadu_pd(lum + b), _mm256_set1_pd(1.0 / 255.0)) : __m256d{};
    const __m256d p = _mm256_loadu_pd(gp + b);
    // unscaleFour's values above the toe, the three channels tested at once (the toe is rare).
    for (int ch = 0; ch < 3; ++ch) {
      given[ch] = lum ? _mm256_mul_pd(_mm256_loadu_pd(m[ch] + b), l) : _mm256_loadu_pd(m[ch] + b);
      r[ch] = unscaleAboveToe(given[ch], p, &above[ch]);
    }
    if (_mm256_movemask_pd(_mm256_and_pd(_mm256_and_pd(above[0], above[1]), above[2])) != 0xF)
      for (int ch = 0; ch < 3; ++ch) r[ch] = unscaleFour(decode, encode, given[ch], gi, gp, b);
    _mm256_storeu_pd(d2 + b, luminanceErrorsOfFour(r[0], r[1], r[2], s + 3 * b));
  }
  for (; b < len; ++b) {
    double r[3];
    for (int ch = 0; ch < 3; ++ch)
      r[ch] = unscaledWith(decode, encode, lum ? m[ch][b] * (lum[b] * (1.0 / 255.0)) : m[ch][b], gi[b], gp[b]);
    d2[b] = luminanceErrorOfOne(r[0], r[1], r[2], s, b);
  }
}

#endif

// The sRGB errors' d2 with the fall-off undone (unscaledErrorsAvx2, the roots gp included)
// where `avx2` and the samples are bytes; false: the caller's loops do it.
template <typename Sample>
SURROGATE_FALLOFF_INLINE bool unscaledErrorsBlock(bool avx2, const double* decode, const double* encode,
                                                  const double* root, const double* const* m, const double* lum,
                                                  const double* gi, double* gp, const Sample* s, double* d2,
                                                  int len) {
#if SURROGATE_NEAR_SRGB_AVX2
  if constexpr (sizeof(Sample) == 1)
    if (avx2) {
      unscaledErrorsAvx2(decode, encode, root, m, lum, gi, gp, s, d2, len);
      return true;
    }
#endif
  return false;
}

// The kernels' entry points: the AVX2 variant where `avx2` (set only where the machine has it).
SURROGATE_FALLOFF_INLINE void rootsBlock(bool avx2, const double* table, const double* f, double* fp, int len) {
#if SURROGATE_NEAR_SRGB_AVX2
  if (avx2) return rootsAvx2(table, f, fp, len);
#endif
  for (int b = 0; b < len; ++b) fp[b] = rootWith(table, f[b]);
}

// The sRGB samples of a block scaled by fi (out[ch], planes), pi = fi^(1/2.4) (rootWith) made
// first.
template <typename Sample>
SURROGATE_FALLOFF_INLINE void scaleSrgbBlock(bool avx2, const double* decode16, const double* encode, const double* root,
                                             const Sample* s, const double* fi, double* pi, double* const* out,
                                             int len) {
#if SURROGATE_NEAR_SRGB_AVX2
  if constexpr (sizeof(Sample) == 1)
    if (avx2) return scaleSrgbAvx2(decode16, encode, root, s, fi, pi, out, len);
#endif
  rootsBlock(avx2, root, fi, pi, len);
  for (int ch = 0; ch < 3; ++ch) scaleSrgb(decode16, encode, s + ch, fi, pi, out[ch], len);
}

SURROGATE_FALLOFF_INLINE void unscaleSrgbBlock(bool avx2, const double* decode, const double* encode, double* m,
                                               const double* gi, const double* gp, int len) {
#if SURROGATE_NEAR_SRGB_AVX2
  if (avx2) return unscaleSrgbAvx2(decode, encode, m, gi, gp, len);
#endif
  unscaleSrgb(decode, encode, m, gi, gp, len);
}

}  // namespace surrogate::fit::falloff
