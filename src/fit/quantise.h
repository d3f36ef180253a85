// Coefficient quantisation: from a coefficient's range over the image to a byte per texel.
//
//   PTM (docs/formats.md, .ptm "Quantisation"; range widened to include 0 so the bias fits):
//       lo' = min(lo, 0), hi' = max(hi, 0)
//       scale = (hi' - lo') / 255,  bias = clamp(round(-lo' / scale), 0, 255)
//       byte  = clamp(round(a / scale + bias), 0, 255);   decoded (byte - bias) * scale
//   HSH (docs/formats.md, .rti "Quantisation"; 0..1 units, float32 tables):
//       SCALE = hi - lo,  BIAS = lo
//       byte  = clamp(round((a - BIAS) / SCALE * 255), 0, 255);  decoded byte/255*SCALE + BIAS
// With the range taken from the data no coefficient clips: the decoding error is at most half
// a step (scale/2 for PTM, SCALE/510 for HSH) plus float rounding.
//
//   PtmQuantisation q = choosePtmQuantisation(-3.2, 140.7);
//   std::uint8_t b = q.quantise(12.5);     // q.decode(b) is within q.scale / 2 of 12.5
#pragma once

#include <cstdint>

namespace surrogate::fit {

namespace detail {
// round(v) clamped to 0..top (NaN gives 0; top at most 2^31 - 1), rounding halves away from
// zero as std::lround does, which is a call into libm; inline because it runs once per
// coefficient or sample. v - trunc(v) is exact for |v| < 2^52. Written as selects on values,
// clamping before the conversion to int (always defined then), so that the row kernels' loops
// over it vectorise (src/fit/row_kernels.h).
inline int roundClamped(double v, double top) {
  const double c = v > 0.0 ? (v < top ? v : top) : 0.0;
  const int whole = static_cast<int>(c);
  return whole + (c - static_cast<double>(whole) >= 0.5 ? 1 : 0);
}

inline std::uint8_t toByte(double v) { return static_cast<std::uint8_t>(roundClamped(v, 255.0)); }
}  // namespace detail

struct PtmQuantisation {
  double scale = 1;
  int bias = 0;
  std::uint8_t quantise(double a) const { return detail::toByte(a / scale + bias); }
  double decode(std::uint8_t byte) const { return (byte - bias) * scale; }
};

struct HshQuantisation {
  float scale = 0;
  float bias = 0;
  std::uint8_t quantise(double a) const {
    if (scale == 0) return 0;
    return detail::toByte((a - static_cast<double>(bias)) / static_cast<double>(scale) * 255.0);
  }
  double decode(std::uint8_t byte) const {
    return byte / 255.0 * static_cast<double>(scale) + static_cast<double>(bias);
  }
};

// `lo` and `hi` are the smallest and largest value of the coefficient over the image.
// A zero range gives scale 1 (PTM) / 0 (HSH); scales below 1e-9 are raised to 1e-9 so the
// header stays short (all values then lie within one step of zero).
PtmQuantisation choosePtmQuantisation(double lo, double hi);
HshQuantisation chooseHshQuantisation(double lo, double hi);

}  // namespace surrogate::fit
