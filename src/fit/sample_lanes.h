// Private to src/fit: what the AVX2 variants of the per-pixel loops share (fit/row_kernels.h,
// fit/error_kernels.h, the maps and previews of fit/normals.cpp and fit/render.cpp): the target
// attribute they are compiled with, the parting of eight interleaved RGB pixels into one lane per
// pixel for each channel, and the rounding of doubles to whole numbers as fit/quantise.h rounds.
//
// SURROGATE_AVX2_TARGET marks a function compiled for AVX2 where the compiler can target it.
// "avx2" alone: the compiler may not fuse a multiply and an add (that needs "fma"), so every
// operation rounds as in the baseline variant, which is the same body compiled for the
// baseline. Elsewhere (kAvx2Compiled false) these are plain copies that activeKernelIsa never
// picks.
#pragma once

#include <cstdint>

#if defined(__x86_64__) && defined(__GNUC__)
#include <immintrin.h>
#define SURROGATE_AVX2_TARGET __attribute__((target("avx2")))
#else
#define SURROGATE_AVX2_TARGET
#endif

namespace surrogate::fit::lanes {

#if defined(__x86_64__) && defined(__GNUC__)
constexpr bool kAvx2Compiled = true;

// Bytes of a, b (and c) picked by byte shuffles with the masks given (-1: a zero byte), ORed.
SURROGATE_AVX2_TARGET inline __m128i pickBytes(__m128i a, __m128i ma, __m128i b, __m128i mb) {
  return _mm_or_si128(_mm_shuffle_epi8(a, ma), _mm_shuffle_epi8(b, mb));
}
SURROGATE_AVX2_TARGET inline __m128i pickBytes(__m128i a, __m128i ma, __m128i b, __m128i mb, __m128i c, __m128i mc) {
  return _mm_or_si128(pickBytes(a, ma, b, mb), _mm_shuffle_epi8(c, mc));
}

// The R, G and B samples of eight interleaved RGB pixels, each channel in eight lanes (16-bit
// samples in 16-bit lanes, bytes in the low eight bytes). Reads the 24 samples and no more.
SURROGATE_AVX2_TARGET inline void channelsOfEight(const std::uint16_t* s, __m128i* r, __m128i* g, __m128i* b) {
  // Sample 3p + c of the 24 is lane (3p + c) % 8 of v[(3p + c) / 8].
  const __m128i v0 = _mm_loadu_si128(reinterpret_cast<const __m128i*>(s));
  const __m128i v1 = _mm_loadu_si128(reinterpret_cast<const __m128i*>(s + 8));
  const __m128i v2 = _mm_loadu_si128(reinterpret_cast<const __m128i*>(s + 16));
  *r = pickBytes(v0, _mm_setr_epi8(0, 1, 6, 7, 12, 13, -1, -1, -1, -1, -1, -1, -1, -1, -1, -1),
                 v1, _mm_setr_epi8(-1, -1, -1, -1, -1, -1, 2, 3, 8, 9, 14, 15, -1, -1, -1, -1),
                 v2, _mm_setr_epi8(-1, -1, -1, -1, -1, -1, -1, -1, -1, -1, -1, -1, 4, 5, 10, 11));
  *g = pickBytes(v0, _mm_setr_epi8(2, 3, 8, 9, 14, 15, -1, -1, -1, -1, -1, -1, -1, -1, -1, -1),
                 v1, _mm_setr_epi8(-1, -1, -1, -1, -1, -1, 4, 5, 10, 11, -1, -1, -1, -1, -1, -1),
                 v2, _mm_setr_epi8(-1, -1, -1, -1, -1, -1, -1, -1, -1, -1, 0, 1, 6, 7, 12, 13));
  *b = pickBytes(v0, _mm_setr_epi8(4, 5, 10, 11, -1, -1, -1, -1, -1, -1, -1, -1, -1, -1, -1, -1),
                 v1, _mm_setr_epi8(-1, -1, -1, -1, 0, 1, 6, 7, 12, 13, -1, -1, -1, -1, -1, -1),
                 v2, _mm_setr_epi8(-1, -1, -1, -1, -1, -1, -1, -1, -1, -1, 2, 3, 8, 9, 14, 15));
}
SURROGATE_AVX2_TARGET inline void channelsOfEight(const std::uint8_t* s, __m128i* r, __m128i* g, __m128i* b) {
  // Sample j of the 24 is byte j % 16 of v[j / 16].
  const __m128i v0 = _mm_loadu_si128(reinterpret_cast<const __m128i*>(s));
  const __m128i v1 = _mm_loadl_epi64(reinterpret_cast<const __m128i*>(s + 16));
  *r = pickBytes(v0, _mm_setr_epi8(0, 3, 6, 9, 12, 15, -1, -1, -1, -1, -1, -1, -1, -1, -1, -1),
                 v1, _mm_setr_epi8(-1, -1, -1, -1, -1, -1, 2, 5, -1, -1, -1, -1, -1, -1, -1, -1));
  *g = pickBytes(v0, _mm_setr_epi8(1, 4, 7, 10, 13, -1, -1, -1, -1, -1, -1, -1, -1, -1, -1, -1),
                 v1, _mm_setr_epi8(-1, -1, -1, -1, -1, 0, 3, 6, -1, -1, -1, -1, -1, -1, -1, -1));
  *b = pickBytes(v0, _mm_setr_epi8(2, 5, 8, 11, 14, -1, -1, -1, -1, -1, -1, -1, -1, -1, -1, -1),
                 v1, _mm_setr_epi8(-1, -1, -1, -1, -1, 1, 4, 7, -1, -1, -1, -1, -1, -1, -1, -1));
}

// Eight lanes of one channel from channelsOfEight as 32-bit integers: the samples' values
// (bytes b as 257 b).
SURROGATE_AVX2_TARGET inline __m256i valuesOfEight(__m128i lanes, const std::uint16_t*) {
  return _mm256_cvtepu16_epi32(lanes);
}
SURROGATE_AVX2_TARGET inline __m256i valuesOfEight(__m128i lanes, const std::uint8_t*) {
  return _mm256_mullo_epi32(_mm256_cvtepu8_epi32(lanes), _mm256_set1_epi32(257));
}

// detail::roundClamped(v, top) (fit/quantise.h) of four values, as doubles: maxpd(v, 0) is v
// where 0 < v, else +0 (NaN and -0 too), minpd(., top) clamps; then the whole part by
// truncation and one more where the rest is at least a half. The quantisation, the normal and
// albedo maps and the previews round their values to integers through this.
SURROGATE_AVX2_TARGET inline __m256d roundClampedFour(__m256d v, __m256d top) {
  const __m256d clamped = _mm256_min_pd(_mm256_max_pd(v, _mm256_setzero_pd()), top);
  const __m256d whole = _mm256_cvtepi32_pd(_mm256_cvttpd_epi32(clamped));
  return _mm256_add_pd(whole, _mm256_and_pd(_mm256_cmp_pd(_mm256_sub_pd(clamped, whole), _mm256_set1_pd(0.5), _CMP_GE_OQ),
                                            _mm256_set1_pd(1.0)));
}
#else
constexpr bool kAvx2Compiled = false;
#endif

}  // namespace surrogate::fit::lanes
