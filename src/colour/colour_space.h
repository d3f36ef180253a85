// Colour spaces of chart measurements: linear sRGB (IEC 61966-2-1 primaries, D65 white), CIE
// XYZ and CIELAB, with Bradford chromatic adaptation between D65 and D50 (the illuminant chart
// reference values are published under).
//
//   Rgb rgb = {0.18, 0.18, 0.18};            // linear sRGB, white = 1
//   Lab lab = labD50FromLinearSrgb(rgb);     // L* ~ 49.5, a* ~ 0, b* ~ 0
//   Rgb back = linearSrgbFromLabD50(lab);
//
// XYZ is scaled so that Y of the white is 1 (L* = 116 f(Y) - 16).
#pragma once

#include <array>

namespace surrogate::colour {

using Rgb = std::array<double, 3>;  // linear light, 0..1 (may go outside for out-of-gamut colours)
using Xyz = std::array<double, 3>;
struct Lab {
  double L = 0, a = 0, b = 0;
};

// sRGB transfer (IEC 61966-2-1): encoded 0..1 <-> linear 0..1 (values outside clamp to 0..1).
double srgbDecode(double encoded);
double srgbEncode(double linear);

Xyz xyzD65FromLinearSrgb(const Rgb& rgb);
Rgb linearSrgbFromXyzD65(const Xyz& xyz);
// Bradford adaptation (von Kries in the Bradford cone space).
Xyz adaptD65ToD50(const Xyz& xyz);
Xyz adaptD50ToD65(const Xyz& xyz);
// CIELAB relative to a white (D50: 0.96422, 1, 0.82521; D65: 0.95047, 1, 1.08883).
Lab labFromXyz(const Xyz& xyz, const Xyz& white);
Xyz xyzFromLab(const Lab& lab, const Xyz& white);
inline constexpr Xyz kWhiteD50{0.96422, 1.0, 0.82521};
inline constexpr Xyz kWhiteD65{0.95047, 1.0, 1.08883};

// The two paths a chart measurement takes: linear sRGB -> XYZ D65 -> Bradford -> XYZ D50 -> Lab.
Lab labD50FromLinearSrgb(const Rgb& rgb);
Rgb linearSrgbFromLabD50(const Lab& lab);

}  // namespace surrogate::colour
