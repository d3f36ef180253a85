// Private to src/fit: the inverse-square fall-off on sRGB-encoded samples (fit/near_fit.h,
// srgbScaled): the curves of IEC 61966-2-1, small tables of them, and the exact multiply-add
// above the toe. Inline, so that each kernel variant of near_fit.cpp compiles them in.
#pragma once

#include <cmath>
#include <vector>

namespace surrogate::fit::falloff {

#define SURROGATE_FALLOFF_INLINE __attribute__((always_inline)) inline

inline double srgbDecodeExact(double v) {  // encoded 0..1 (and beyond) -> linear
  if (v < 0) return -srgbDecodeExact(-v);
  return v <= 0.04045 ? v / 12.92 : std::pow((v + 0.055) / 1.055, 2.4);
}
inline double srgbEncodeExact(double l) {  // linear -> encoded
  if (l < 0) return -srgbEncodeExact(-l);
  return l <= 0.0031308 ? 12.92 * l : 1.055 * std::pow(l, 1 / 2.4) - 0.055;
}

// The tables of srgbScaled and srgbUnscaled, made once (the same values on every call), small
// enough to stay in the first-level cache: a 512 KB table read at random cost the fit as much as
// its arithmetic. Encoding is tabulated against u = sqrt(L), where it is smooth enough for 4096
// steps (interpolation error under 2e-6 of full scale); decoding against the encoded value.
// The interpolated tables hold pairs (f_j, f_{j+1} - f_j), the difference made here as the
// interpolation made it before: one 16-byte read a value, the same bits.
constexpr int kTable = 4096;
constexpr double kEncodeRangeU = 2.8284271247461903;  // sqrt(8): linear values up to 8 tabulated
constexpr double kDecodeRange = 4.0;                   // encoded values (0..1 full scale) up to 4
constexpr double kRootRangeU = 8.0;  // sqrt of the largest factor tabulated (64)
inline std::vector<double> tablePairs(const std::vector<double>& f) {
  std::vector<double> p(2 * f.size());
  for (std::size_t j = 0; j < f.size(); ++j) {
    p[2 * j] = f[j];
    p[2 * j + 1] = j + 1 < f.size() ? f[j + 1] - f[j] : 0.0;
  }
  return p;
}
struct SrgbTables {
  std::vector<double> decode16, encode, decode, root;  // the last three as pairs
  SrgbTables() : decode16(65536) {
    std::vector<double> e(kTable + 1), d(kTable + 1), r(kTable + 1);
    for (int v = 0; v < 65536; ++v) decode16[v] = srgbDecodeExact(v / 65535.0);
    for (int j = 0; j <= kTable; ++j) {
      const double u = kEncodeRangeU * j / kTable;
      e[j] = srgbEncodeExact(u * u);
      d[j] = srgbDecodeExact(kDecodeRange * j / kTable);
      const double w = kRootRangeU * j / kTable;
      r[j] = std::pow(w * w, 1 / 2.4);
    }
    encode = tablePairs(e);
    decode = tablePairs(d);
    root = tablePairs(r);
  }
};
inline const SrgbTables& srgbTables() {
  static const SrgbTables tables;
  return tables;
}

// f(x) from the pairs of f at range * j / kTable, linearly interpolated (x in [0, range)).
SURROGATE_FALLOFF_INLINE double interpolated(const double* pairs, double range, double x) {
  const double at = x * (kTable / range);
  const int j = static_cast<int>(at);
  const double u = at - j;
  return pairs[2 * j] + u * pairs[2 * j + 1];
}

SURROGATE_FALLOFF_INLINE double encodeLinear(const double* encode, double l) {
  if (!(l >= 0 && l < 8.0)) return srgbEncodeExact(l);
  return interpolated(encode, kEncodeRangeU, std::sqrt(l));
}

SURROGATE_FALLOFF_INLINE double decodeEncoded(const double* decode, double v) {
  if (!(v >= 0 && v < kDecodeRange)) return srgbDecodeExact(v);
  return interpolated(decode, kDecodeRange, v);
}

// f^(1/2.4), against sqrt(f) (smooth enough for 4096 steps: relative error under 1e-8).
SURROGATE_FALLOFF_INLINE double rootWith(const double* root, double f) {
  if (!(f >= 0 && f < kRootRangeU * kRootRangeU)) return std::pow(f, 1 / 2.4);
  return interpolated(root, kRootRangeU, std::sqrt(f));
}

// srgbScaled and srgbUnscaled (near_fit.h) on the tables. Above the curve's linear toe, where
// v = 1.055 L^(1/2.4) - 0.055, scaling L by f gives exactly (v + 0.055) f^(1/2.4) - 0.055: one
// multiply-add a sample, with fp = f^(1/2.4) shared by the pixel's three channels. In the toe
// (v or the result at most 0.04045, L at most 0.0031308) the tables.
constexpr double kToe = 0.04045;
SURROGATE_FALLOFF_INLINE double scaledWith(const double* decode16, const double* encode, unsigned v16, double f,
                                   double fp) {
  const double v = v16 * (1.0 / 65535.0);
  if (v > kToe) {
    const double y = (v + 0.055) * fp - 0.055;
    if (y > kToe) return 65535.0 * y;
  }
  return 65535.0 * encodeLinear(encode, decode16[v16] * f);
}
SURROGATE_FALLOFF_INLINE double unscaledWith(const double* decode, const double* encode, double m255, double g,
                                     double gp) {
  const double v = m255 * (1.0 / 255.0);
  if (v > kToe) {
    const double y = (v + 0.055) * gp - 0.055;
    if (y > kToe) return 255.0 * y;
  }
  return 255.0 * encodeLinear(encode, decodeEncoded(decode, v) * g);
}

// One row's view of the model: the nodes interpolated to the row (R, cols x stride), their

}  // namespace surrogate::fit::falloff
