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

// interpolated(table, range, x) lane by lane, x in [0, range).
SURROGATE_NEAR_AVX2_INLINE __m256d interpolatedAvx2(const double* table, double range, __m256d x) {
  const __m256d at = _mm256_mul_pd(x, _mm256_set1_pd(kTable / range));
  const __m128i j = _mm256_cvttpd_epi32(at);  // static_cast<int>, at >= 0
  const __m256d u = _mm256_sub_pd(at, _mm256_cvtepi32_pd(j));
  alignas(16) int at4[4];
  _mm_store_si128(reinterpret_cast<__m128i*>(at4), j);
  const __m256d t0 = _mm256_setr_pd(table[at4[0]], table[at4[1]], table[at4[2]], table[at4[3]]);
  const __m256d t1 = _mm256_setr_pd(table[at4[0] + 1], table[at4[1] + 1], table[at4[2] + 1], table[at4[3] + 1]);
  return _mm256_add_pd(t0, _mm256_mul_pd(u, _mm256_sub_pd(t1, t0)));
}

// fp[b] = rootWith(table, f[b]), b < len.
SURROGATE_NEAR_AVX2_BLOCK inline void rootsAvx2(const double* table, const double* f, double* fp, int len) {
  const __m256d zero = _mm256_setzero_pd(), top = _mm256_set1_pd(kRootRangeU * kRootRangeU);
  int b = 0;
  for (; b + 4 <= len; b += 4) {
    const __m256d v = _mm256_loadu_pd(f + b);
    const __m256d inside = _mm256_and_pd(_mm256_cmp_pd(v, zero, _CMP_GE_OQ), _mm256_cmp_pd(v, top, _CMP_LT_OQ));
    if (_mm256_movemask_pd(inside) != 0xF) {
      for (int j = b; j < b + 4; ++j) fp[j] = rootWith(table, f[j]);
      continue;
    }
    _mm256_storeu_pd(fp + b, interpolatedAvx2(table, kRootRangeU, _mm256_sqrt_pd(v)));
  }
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

// out[ch][b] = scaledWith(the 16-bit value of channel ch of pixel b, fi[b], pi[b]) for the
// interleaved 8-bit RGB row s, b < len.
SURROGATE_NEAR_AVX2_BLOCK inline void scaleSrgbAvx2(const double* decode16, const double* encode,
                                                    const std::uint8_t* s, const double* fi, const double* pi,
                                                    double* const* out, int len) {
  const __m256d toe = _mm256_set1_pd(kToe), offset = _mm256_set1_pd(0.055);
  // The row's next block (the caller's next call for this photograph): dozens of photographs'
  // rows are more streams than the hardware prefetcher follows.
  for (int ahead = 0; ahead < 3 * len; ahead += 64) __builtin_prefetch(s + 3 * len + ahead);
  int b = 0;
  for (; b + 4 <= len; b += 4) {
    __m256d channel[3];
    channelsOfFour(s + 3 * b, channel);
    const __m256d p = _mm256_loadu_pd(pi + b);
    for (int ch = 0; ch < 3; ++ch) {
      // sampleValue(byte) = 257 byte, exact as a double either way; then v = value / 65535.
      const __m256d v =
          _mm256_mul_pd(_mm256_mul_pd(channel[ch], _mm256_set1_pd(257.0)), _mm256_set1_pd(1.0 / 65535.0));
      const __m256d y = _mm256_sub_pd(_mm256_mul_pd(_mm256_add_pd(v, offset), p), offset);
      const __m256d above = _mm256_and_pd(_mm256_cmp_pd(v, toe, _CMP_GT_OQ), _mm256_cmp_pd(y, toe, _CMP_GT_OQ));
      const __m256d fast = _mm256_mul_pd(y, _mm256_set1_pd(65535.0));
      if (_mm256_movemask_pd(above) == 0xF) {
        _mm256_storeu_pd(out[ch] + b, fast);
        continue;
      }
      // Lanes in the toe: 65535 encodeLinear(decode16[value] f), in linear light.
      const __m256d l = _mm256_mul_pd(
          _mm256_setr_pd(decode16[sampleValue(s[3 * b + ch])], decode16[sampleValue(s[3 * b + 3 + ch])],
                         decode16[sampleValue(s[3 * b + 6 + ch])], decode16[sampleValue(s[3 * b + 9 + ch])]),
          _mm256_loadu_pd(fi + b));
      const __m256d inside = _mm256_and_pd(_mm256_cmp_pd(l, _mm256_setzero_pd(), _CMP_GE_OQ),
                                           _mm256_cmp_pd(l, _mm256_set1_pd(8.0), _CMP_LT_OQ));
      // A lane past the table reads it at 0, and is then done by the formula (scaledWith).
      const __m256d slow = _mm256_mul_pd(_mm256_set1_pd(65535.0),
                                         interpolatedAvx2(encode, kEncodeRangeU, _mm256_sqrt_pd(_mm256_and_pd(l, inside))));
      _mm256_storeu_pd(out[ch] + b, _mm256_blendv_pd(slow, fast, above));
      const int done = _mm256_movemask_pd(_mm256_or_pd(above, inside));
      for (int j = 0; j < 4; ++j)
        if (!(done >> j & 1)) out[ch][b + j] = scaledWith(decode16, encode, sampleValue(s[3 * (b + j) + ch]), fi[b + j], pi[b + j]);
    }
  }
  for (; b < len; ++b)
    for (int ch = 0; ch < 3; ++ch) out[ch][b] = scaledWith(decode16, encode, sampleValue(s[3 * b + ch]), fi[b], pi[b]);
}

// m[b] = unscaledWith(m[b], gi[b], gp[b]) in place, b < len.
SURROGATE_NEAR_AVX2_BLOCK inline void unscaleSrgbAvx2(const double* decode, const double* encode, double* m,
                                                      const double* gi, const double* gp, int len) {
  const __m256d toe = _mm256_set1_pd(kToe), offset = _mm256_set1_pd(0.055);
  int b = 0;
  for (; b + 4 <= len; b += 4) {
    const __m256d v = _mm256_mul_pd(_mm256_loadu_pd(m + b), _mm256_set1_pd(1.0 / 255.0));
    const __m256d y = _mm256_sub_pd(_mm256_mul_pd(_mm256_add_pd(v, offset), _mm256_loadu_pd(gp + b)), offset);
    const __m256d above = _mm256_and_pd(_mm256_cmp_pd(v, toe, _CMP_GT_OQ), _mm256_cmp_pd(y, toe, _CMP_GT_OQ));
    const __m256d fast = _mm256_mul_pd(_mm256_set1_pd(255.0), y);
    if (_mm256_movemask_pd(above) == 0xF) {
      _mm256_storeu_pd(m + b, fast);
      continue;
    }
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
    double given[4];
    _mm256_storeu_pd(given, _mm256_loadu_pd(m + b));
    _mm256_storeu_pd(m + b, _mm256_blendv_pd(slow, fast, above));
    const int done = _mm256_movemask_pd(_mm256_or_pd(above, inside));
    for (int j = 0; j < 4; ++j)
      if (!(done >> j & 1)) m[b + j] = unscaledWith(decode, encode, given[j], gi[b + j], gp[b + j]);
  }
  for (; b < len; ++b) m[b] = unscaledWith(decode, encode, m[b], gi[b], gp[b]);
}

// std::clamp(v, 0, 255) lane by lane, as near_fit.cpp's clamp255.
SURROGATE_NEAR_AVX2_INLINE __m256d clamp(__m256d v) {
  const __m256d zero = _mm256_setzero_pd(), top = _mm256_set1_pd(255.0);
  const __m256d low = _mm256_blendv_pd(v, zero, _mm256_cmp_pd(v, zero, _CMP_LT_OQ));
  return _mm256_blendv_pd(low, top, _mm256_cmp_pd(top, low, _CMP_LT_OQ));
}

// d2[b] = (model - captured)^2, b < len, for the errors of sRGB samples (near_fit.cpp's
// channelErrors and lrgbErrors, the fall-off already undone): model = the Rec. 709 luminance of
// the clamped channels r0, r1, r2; captured = that of the 8-bit RGB row s in 0..255 units.
SURROGATE_NEAR_AVX2_BLOCK inline void luminanceErrorsAvx2(const double* r0, const double* r1, const double* r2,
                                                          const std::uint8_t* s, double* d2, int len) {
  int b = 0;
  for (; b + 4 <= len; b += 4) {
    __m256d value[3];  // sampleValue: 257 byte, exact
    channelsOfFour(s + 3 * b, value);
    for (int ch = 0; ch < 3; ++ch) value[ch] = _mm256_mul_pd(value[ch], _mm256_set1_pd(257.0));
    const __m256d model = _mm256_add_pd(
        _mm256_add_pd(_mm256_mul_pd(_mm256_set1_pd(kLumR), clamp(_mm256_loadu_pd(r0 + b))),
                      _mm256_mul_pd(_mm256_set1_pd(kLumG), clamp(_mm256_loadu_pd(r1 + b)))),
        _mm256_mul_pd(_mm256_set1_pd(kLumB), clamp(_mm256_loadu_pd(r2 + b))));
    const __m256d captured = _mm256_mul_pd(
        _mm256_add_pd(_mm256_add_pd(_mm256_mul_pd(_mm256_set1_pd(kLumR), value[0]),
                                    _mm256_mul_pd(_mm256_set1_pd(kLumG), value[1])),
                      _mm256_mul_pd(_mm256_set1_pd(kLumB), value[2])),
        _mm256_set1_pd(1.0 / 257.0));
    const __m256d d = _mm256_sub_pd(model, captured);
    _mm256_storeu_pd(d2 + b, _mm256_mul_pd(d, d));
  }
  for (; b < len; ++b) {
    auto one = [](double v) { const double l = v < 0.0 ? 0.0 : v; return 255.0 < l ? 255.0 : l; };
    const double model = kLumR * one(r0[b]) + kLumG * one(r1[b]) + kLumB * one(r2[b]);
    const double captured =
        (kLumR * sampleValue(s[3 * b]) + kLumG * sampleValue(s[3 * b + 1]) + kLumB * sampleValue(s[3 * b + 2])) *
        (1.0 / 257.0);
    d2[b] = (model - captured) * (model - captured);
  }
}

#endif

// The sRGB errors' d2 (luminanceErrorsAvx2) where `avx2` and the samples are bytes; false: the
// caller's loop does it.
template <typename Sample>
SURROGATE_FALLOFF_INLINE bool luminanceErrorsBlock(bool avx2, const double* r0, const double* r1, const double* r2,
                                                   const Sample* s, double* d2, int len) {
#if SURROGATE_NEAR_SRGB_AVX2
  if constexpr (sizeof(Sample) == 1)
    if (avx2) {
      luminanceErrorsAvx2(r0, r1, r2, s, d2, len);
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

template <typename Sample>
SURROGATE_FALLOFF_INLINE void scaleSrgbBlock(bool avx2, const double* decode16, const double* encode, const Sample* s,
                                             const double* fi, const double* pi, double* const* out, int len) {
#if SURROGATE_NEAR_SRGB_AVX2
  if constexpr (sizeof(Sample) == 1)
    if (avx2) return scaleSrgbAvx2(decode16, encode, s, fi, pi, out, len);
#endif
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
