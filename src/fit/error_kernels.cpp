#include "fit/error_kernels.h"

#include "fit/sample_lanes.h"
#include "fit/stream_fit.h"

// Compiled with -fno-trapping-math (src/fit/CMakeLists.txt), as row_kernels.cpp: the clamps
// may become vector selects; no value changes.

namespace surrogate::fit {

namespace {

constexpr float kR = static_cast<float>(kLumR), kG = static_cast<float>(kLumG), kB = static_cast<float>(kLumB);
constexpr float kInv255 = 1.0f / 255.0f, kInv257 = 1.0f / 257.0f;
// The most terms a per-channel model has (HSH order 3: 9; PTM RGB: 6).
constexpr int kMaxTerms = 16;

inline float clampLevel(float v) {
  const float low = v < 0.0f ? 0.0f : v;
  return 255.0f < low ? 255.0f : low;
}

// A sample's 16-bit value (row_kernels.h sampleValue: bytes b as 257 b), exact as a float.
template <typename Sample>
inline float valueOf(Sample s) { return static_cast<float>(sampleValue(s)); }

// d(x) of error_kernels.h for one pixel, from its three channel values v.
template <typename Sample>
__attribute__((always_inline)) inline float difference(const float v[3], const Sample* s) {
  const float model = kR * clampLevel(v[0]) + kG * clampLevel(v[1]) + kB * clampLevel(v[2]);
  const float captured = (kR * valueOf(s[0]) + kG * valueOf(s[1]) + kB * valueOf(s[2])) * kInv257;
  return model - captured;
}

template <typename Sample>
__attribute__((always_inline)) inline float lrgbDifference(const float* const lum[6], const float* const colour[3],
                                                          const float basis[6], const Sample* s, std::size_t x) {
  float l = basis[0] * lum[0][x];
  for (int k = 1; k < 6; ++k) l = l + basis[k] * lum[k][x];
  const float t = l * kInv255;
  const float v[3] = {colour[0][x] * t, colour[1][x] * t, colour[2][x] * t};
  return difference(v, s + 3 * x);
}

template <typename Sample>
__attribute__((always_inline)) inline float channelDifference(const float* const* planes, int terms,
                                                             const float* basis, const Sample* s, std::size_t x) {
  float v[3];
  for (int c = 0; c < 3; ++c) {
    v[c] = basis[0] * planes[c][x];
    for (int k = 1; k < terms; ++k) v[c] = v[c] + basis[k] * planes[3 * k + c][x];
  }
  return difference(v, s + 3 * x);
}

// The lane sums of error_kernels.h, from pixel `from` (a multiple of 8, the lanes already
// holding the pixels before it) to the end, one pixel's difference at a time.
template <typename Difference>
__attribute__((always_inline)) inline double laneSums(double part[8], std::size_t from, std::size_t pixels,
                                                      Difference diff) {
  std::size_t x = from;
  for (; x + 8 <= pixels; x += 8)
    for (std::size_t j = 0; j < 8; ++j) {
      const float d = diff(x + j);
      part[j] += static_cast<double>(d * d);
    }
  double sum = ((part[0] + part[1]) + (part[2] + part[3])) + ((part[4] + part[5]) + (part[6] + part[7]));
  for (; x < pixels; ++x) {
    const float d = diff(x);
    sum += static_cast<double>(d * d);
  }
  return sum;
}

template <typename Sample>
double lrgbBaseline(const float* const lum[6], const float* const colour[3], const float basis[6], const Sample* s,
                    std::size_t pixels) {
  double part[8] = {0, 0, 0, 0, 0, 0, 0, 0};
  return laneSums(part, 0, pixels, [&](std::size_t x) { return lrgbDifference(lum, colour, basis, s, x); });
}

template <typename Sample>
double channelBaseline(const float* const* planes, int terms, const float* basis, const Sample* s,
                       std::size_t pixels) {
  double part[8] = {0, 0, 0, 0, 0, 0, 0, 0};
  return laneSums(part, 0, pixels,
                  [&](std::size_t x) { return channelDifference(planes, terms, basis, s, x); });
}

#if defined(__x86_64__) && defined(__GNUC__)
SURROGATE_AVX2_TARGET inline __m256 clampEight(__m256 v) {
  // max(0, v) is (0 > v ? 0 : v) and min(255, low) is (255 < low ? 255 : low): clampLevel's
  // comparisons, NaN included.
  return _mm256_min_ps(_mm256_set1_ps(255.0f), _mm256_max_ps(_mm256_setzero_ps(), v));
}

// d of eight pixels from their channel values and samples.
template <typename Sample>
SURROGATE_AVX2_TARGET inline __m256 differenceOfEight(__m256 vr, __m256 vg, __m256 vb, const Sample* s) {
  const __m256 kr = _mm256_set1_ps(kR), kg = _mm256_set1_ps(kG), kb = _mm256_set1_ps(kB);
  const __m256 model = _mm256_add_ps(_mm256_add_ps(_mm256_mul_ps(kr, clampEight(vr)), _mm256_mul_ps(kg, clampEight(vg))),
                                     _mm256_mul_ps(kb, clampEight(vb)));
  __m128i r, g, b;
  lanes::channelsOfEight(s, &r, &g, &b);
  const __m256 sr = _mm256_cvtepi32_ps(lanes::valuesOfEight(r, s));
  const __m256 sg = _mm256_cvtepi32_ps(lanes::valuesOfEight(g, s));
  const __m256 sb = _mm256_cvtepi32_ps(lanes::valuesOfEight(b, s));
  const __m256 captured = _mm256_mul_ps(
      _mm256_add_ps(_mm256_add_ps(_mm256_mul_ps(kr, sr), _mm256_mul_ps(kg, sg)), _mm256_mul_ps(kb, sb)),
      _mm256_set1_ps(kInv257));
  return _mm256_sub_ps(model, captured);
}

// Adds d^2 of eight pixels to lanes 0-3 (low) and 4-7 (high), in double.
SURROGATE_AVX2_TARGET inline void addSquares(__m256 d, __m256d* low, __m256d* high) {
  const __m256 d2 = _mm256_mul_ps(d, d);
  *low = _mm256_add_pd(*low, _mm256_cvtps_pd(_mm256_castps256_ps128(d2)));
  *high = _mm256_add_pd(*high, _mm256_cvtps_pd(_mm256_extractf128_ps(d2, 1)));
}

SURROGATE_AVX2_TARGET inline void storeLanes(__m256d low, __m256d high, double part[8]) {
  _mm256_storeu_pd(part, low);
  _mm256_storeu_pd(part + 4, high);
}

template <typename Sample>
SURROGATE_AVX2_TARGET double lrgbAvx2(const float* const lum[6], const float* const colour[3], const float basis[6],
                                      const Sample* s, std::size_t pixels) {
  __m256 b[6];
  for (int k = 0; k < 6; ++k) b[k] = _mm256_set1_ps(basis[k]);
  __m256d low = _mm256_setzero_pd(), high = _mm256_setzero_pd();
  std::size_t x = 0;
  for (; x + 8 <= pixels; x += 8) {
    __m256 l = _mm256_mul_ps(b[0], _mm256_loadu_ps(lum[0] + x));
    for (int k = 1; k < 6; ++k) l = _mm256_add_ps(l, _mm256_mul_ps(b[k], _mm256_loadu_ps(lum[k] + x)));
    const __m256 t = _mm256_mul_ps(l, _mm256_set1_ps(kInv255));
    addSquares(differenceOfEight(_mm256_mul_ps(_mm256_loadu_ps(colour[0] + x), t),
                                 _mm256_mul_ps(_mm256_loadu_ps(colour[1] + x), t),
                                 _mm256_mul_ps(_mm256_loadu_ps(colour[2] + x), t), s + 3 * x),
               &low, &high);
  }
  double part[8];
  storeLanes(low, high, part);
  return laneSums(part, x, pixels, [&](std::size_t p) { return lrgbDifference(lum, colour, basis, s, p); });
}

template <typename Sample>
SURROGATE_AVX2_TARGET double channelAvx2(const float* const* planes, int terms, const float* basis, const Sample* s,
                                         std::size_t pixels) {
  __m256 b[kMaxTerms];
  for (int k = 0; k < terms; ++k) b[k] = _mm256_set1_ps(basis[k]);
  __m256d low = _mm256_setzero_pd(), high = _mm256_setzero_pd();
  std::size_t x = 0;
  for (; x + 8 <= pixels; x += 8) {
    __m256 v[3];
    for (int c = 0; c < 3; ++c) {
      v[c] = _mm256_mul_ps(b[0], _mm256_loadu_ps(planes[c] + x));
      for (int k = 1; k < terms; ++k) v[c] = _mm256_add_ps(v[c], _mm256_mul_ps(b[k], _mm256_loadu_ps(planes[3 * k + c] + x)));
    }
    addSquares(differenceOfEight(v[0], v[1], v[2], s + 3 * x), &low, &high);
  }
  double part[8];
  storeLanes(low, high, part);
  return laneSums(part, x, pixels, [&](std::size_t p) { return channelDifference(planes, terms, basis, s, p); });
}
#else
template <typename Sample>
double lrgbAvx2(const float* const lum[6], const float* const colour[3], const float basis[6], const Sample* s,
                std::size_t pixels) {
  return lrgbBaseline(lum, colour, basis, s, pixels);
}
template <typename Sample>
double channelAvx2(const float* const* planes, int terms, const float* basis, const Sample* s, std::size_t pixels) {
  return channelBaseline(planes, terms, basis, s, pixels);
}
#endif

template <typename Sample>
double lrgbOf(const float* const lum[6], const float* const colour[3], const float basis[6], const Sample* s,
              std::size_t pixels, KernelIsa isa) {
  if (isa == KernelIsa::Avx2) return lrgbAvx2(lum, colour, basis, s, pixels);
  return lrgbBaseline(lum, colour, basis, s, pixels);
}

template <typename Sample>
double channelOf(const float* const* planes, int terms, const float* basis, const Sample* s, std::size_t pixels,
                 KernelIsa isa) {
  if (terms < 1 || terms > kMaxTerms) return 0;  // no basis of Surrogate's has another count
  if (isa == KernelIsa::Avx2) return channelAvx2(planes, terms, basis, s, pixels);
  return channelBaseline(planes, terms, basis, s, pixels);
}

}  // namespace

double lrgbSquaredErrorSum(const float* const lum[6], const float* const colour[3], const float basis[6],
                           const std::uint16_t* s, std::size_t pixels, KernelIsa isa) {
  return lrgbOf(lum, colour, basis, s, pixels, isa);
}
double lrgbSquaredErrorSum(const float* const lum[6], const float* const colour[3], const float basis[6],
                           const std::uint8_t* s, std::size_t pixels, KernelIsa isa) {
  return lrgbOf(lum, colour, basis, s, pixels, isa);
}

double channelSquaredErrorSum(const float* const* planes, int terms, const float* basis, const std::uint16_t* s,
                              std::size_t pixels, KernelIsa isa) {
  return channelOf(planes, terms, basis, s, pixels, isa);
}
double channelSquaredErrorSum(const float* const* planes, int terms, const float* basis, const std::uint8_t* s,
                              std::size_t pixels, KernelIsa isa) {
  return channelOf(planes, terms, basis, s, pixels, isa);
}

}  // namespace surrogate::fit
