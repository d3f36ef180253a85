// Colour spaces of chart measurements: sRGB transfer, linear sRGB <-> XYZ D65, Bradford D65 <->
// D50 and CIELAB. See colour_space.h.
//
// The sRGB matrix is derived here from the IEC 61966-2-1 primaries (x, y: red 0.64 0.33, green
// 0.30 0.60, blue 0.15 0.06) scaled so that RGB (1, 1, 1) lands exactly on kWhiteD65, rather
// than typed in from the standard's 4-digit table: that way a neutral stays neutral through every
// step (the 4-digit matrix puts white at 0.9505, 1, 1.0890, a few thousandths of a* b* off D65).
// The result agrees with the standard's table to its 4 digits (tests/colour pins both).
#include "colour/colour_space.h"

#include <algorithm>
#include <cmath>

namespace surrogate::colour {
namespace {

using Matrix = std::array<std::array<double, 3>, 3>;

Xyz multiply(const Matrix& m, const Xyz& v) {
  return {m[0][0] * v[0] + m[0][1] * v[1] + m[0][2] * v[2],
          m[1][0] * v[0] + m[1][1] * v[1] + m[1][2] * v[2],
          m[2][0] * v[0] + m[2][1] * v[1] + m[2][2] * v[2]};
}

Matrix product(const Matrix& a, const Matrix& b) {
  Matrix r{};
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j)
      for (int k = 0; k < 3; ++k) r[i][j] += a[i][k] * b[k][j];
  return r;
}

Matrix inverse(const Matrix& m) {
  const double c00 = m[1][1] * m[2][2] - m[1][2] * m[2][1];
  const double c01 = m[1][2] * m[2][0] - m[1][0] * m[2][2];
  const double c02 = m[1][0] * m[2][1] - m[1][1] * m[2][0];
  const double det = m[0][0] * c00 + m[0][1] * c01 + m[0][2] * c02;
  Matrix r{};
  r[0][0] = c00 / det;
  r[0][1] = (m[0][2] * m[2][1] - m[0][1] * m[2][2]) / det;
  r[0][2] = (m[0][1] * m[1][2] - m[0][2] * m[1][1]) / det;
  r[1][0] = c01 / det;
  r[1][1] = (m[0][0] * m[2][2] - m[0][2] * m[2][0]) / det;
  r[1][2] = (m[0][2] * m[1][0] - m[0][0] * m[1][2]) / det;
  r[2][0] = c02 / det;
  r[2][1] = (m[0][1] * m[2][0] - m[0][0] * m[2][1]) / det;
  r[2][2] = (m[0][0] * m[1][1] - m[0][1] * m[1][0]) / det;
  return r;
}

// Columns: the primaries' XYZ at Y = 1, each scaled so that their sum is the white.
Matrix srgbToXyz() {
  const double xy[3][2] = {{0.64, 0.33}, {0.30, 0.60}, {0.15, 0.06}};
  Matrix p{};
  for (int c = 0; c < 3; ++c) {
    p[0][c] = xy[c][0] / xy[c][1];
    p[1][c] = 1.0;
    p[2][c] = (1.0 - xy[c][0] - xy[c][1]) / xy[c][1];
  }
  const Xyz s = multiply(inverse(p), kWhiteD65);
  for (int r = 0; r < 3; ++r)
    for (int c = 0; c < 3; ++c) p[r][c] *= s[c];
  return p;
}

// The Bradford cone response matrix (Lam 1985, as used by ICC v4 and Lindbloom).
constexpr Matrix kBradford{{{0.8951, 0.2664, -0.1614},
                            {-0.7502, 1.7135, 0.0367},
                            {0.0389, -0.0685, 1.0296}}};

Matrix bradford(const Xyz& from, const Xyz& to) {
  const Xyz a = multiply(kBradford, from);
  const Xyz b = multiply(kBradford, to);
  Matrix scale{};
  for (int i = 0; i < 3; ++i) scale[i][i] = b[i] / a[i];
  return product(inverse(kBradford), product(scale, kBradford));
}

struct Matrices {
  Matrix toXyz = srgbToXyz();
  Matrix fromXyz = inverse(toXyz);
  Matrix d65ToD50 = bradford(kWhiteD65, kWhiteD50);
  Matrix d50ToD65 = bradford(kWhiteD50, kWhiteD65);
};
const Matrices& matrices() {
  static const Matrices m;
  return m;
}

// CIE's exact constants (CIE 15:2004 note; Lindbloom): the knee of the cube root.
constexpr double kEpsilon = 216.0 / 24389.0;
constexpr double kKappa = 24389.0 / 27.0;

double labF(double t) { return t > kEpsilon ? std::cbrt(t) : (kKappa * t + 16.0) / 116.0; }
double labFInverse(double f) {
  const double cube = f * f * f;
  return cube > kEpsilon ? cube : (116.0 * f - 16.0) / kKappa;
}

}  // namespace

double srgbDecode(double encoded) {
  const double v = std::clamp(encoded, 0.0, 1.0);
  return v <= 0.04045 ? v / 12.92 : std::pow((v + 0.055) / 1.055, 2.4);
}

double srgbEncode(double linear) {
  const double v = std::clamp(linear, 0.0, 1.0);
  return v <= 0.0031308 ? v * 12.92 : 1.055 * std::pow(v, 1.0 / 2.4) - 0.055;
}

Xyz xyzD65FromLinearSrgb(const Rgb& rgb) { return multiply(matrices().toXyz, rgb); }
Rgb linearSrgbFromXyzD65(const Xyz& xyz) { return multiply(matrices().fromXyz, xyz); }
Xyz adaptD65ToD50(const Xyz& xyz) { return multiply(matrices().d65ToD50, xyz); }
Xyz adaptD50ToD65(const Xyz& xyz) { return multiply(matrices().d50ToD65, xyz); }

Lab labFromXyz(const Xyz& xyz, const Xyz& white) {
  const double fx = labF(xyz[0] / white[0]);
  const double fy = labF(xyz[1] / white[1]);
  const double fz = labF(xyz[2] / white[2]);
  return {116.0 * fy - 16.0, 500.0 * (fx - fy), 200.0 * (fy - fz)};
}

Xyz xyzFromLab(const Lab& lab, const Xyz& white) {
  const double fy = (lab.L + 16.0) / 116.0;
  const double fx = fy + lab.a / 500.0;
  const double fz = fy - lab.b / 200.0;
  // Y from L* directly below the knee (L* <= 8), as CIE writes it, so dark greys round-trip.
  const double y = lab.L > kKappa * kEpsilon ? fy * fy * fy : lab.L / kKappa;
  return {white[0] * labFInverse(fx), white[1] * y, white[2] * labFInverse(fz)};
}

Lab labD50FromLinearSrgb(const Rgb& rgb) {
  return labFromXyz(adaptD65ToD50(xyzD65FromLinearSrgb(rgb)), kWhiteD50);
}

Rgb linearSrgbFromLabD50(const Lab& lab) {
  return linearSrgbFromXyzD65(adaptD50ToD65(xyzFromLab(lab, kWhiteD50)));
}

}  // namespace surrogate::colour
