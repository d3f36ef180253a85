// Test support: the PTM and HSH light bases written out from their published definitions,
// independent of src/fit (nothing here calls surrogate::fit), so that a test comparing
// fit::ptmBasis / fit::hshBasis / fit::render / fit::fitHsh with these functions checks the
// code against the definitions, not against itself. docs/hrti-math.md ("The PTM basis",
// "The HSH basis") restates them.
//
// Light convention (docs/formats.md, "Light directions"): (lx, ly, lz) with x to the right
// of the image, y to its TOP, z towards the camera; the vector need not be unit length.
//
// PTM (Malzbender, Gelb, Wolters, "Polynomial Texture Maps", SIGGRAPH 2001, and HP's "PTM
// File Format" v1.2): (lu, lv) = (lx, ly) of the unit light vector; the six coefficients
// a0..a5 of a file multiply, in this order,
//     lu^2, lv^2, lu*lv, lu, lv, 1.
//
// HSH (Gautron, Krivanek, Pattanaik, Bouatouch, "A Novel Hemispherical Basis for Accurate and
// Efficient Rendering", EGSR 2004; term order and signs of CHI's RTIViewer, util.h getHSH, and
// of relight's src/rti.cpp lightWeightsHsh, which agree on H0..H8):
//     theta = acos(lz) of the unit vector, clamped to at most pi/2 - 0.01 (relight's renderer),
//     phi   = atan2(ly, lx),
//     c = cos(theta), s = sqrt(c - c^2), t = 2c - 1.
// Written two ways:
//  (1) hshTable: RTIViewer's closed forms, term by term (order 2 = H0..H3, order 3 = H0..H8,
//      order 4 = H0..H15):
//        H0  = 1/sqrt(2 pi)
//        H1  = sqrt(6/pi)     cos(phi)  s          H3  = sqrt(6/pi)     sin(phi)  s
//        H2  = sqrt(3/(2 pi)) t
//        H4  = sqrt(30/pi)    cos(2phi) (c^2 - c)  H8  = sqrt(30/pi)    sin(2phi) (c^2 - c)
//        H5  = sqrt(30/pi)    cos(phi)  t s        H7  = sqrt(30/pi)    sin(phi)  t s
//        H6  = sqrt(5/(2 pi)) (6c^2 - 6c + 1)
//        H9  = 2 sqrt(35/pi)  cos(3phi) (c - c^2)^(3/2)
//        H15 = 2 sqrt(35/pi)  sin(3phi) (c - c^2)^(3/2)
//        H10 = sqrt(210/pi)   cos(2phi) t (c^2 - c)
//        H14 = sqrt(210/pi)   sin(2phi) t (c^2 - c)
//        H11 = 2 sqrt(21/pi)  cos(phi)  s (5c^2 - 5c + 1)
//        H13 = 2 sqrt(21/pi)  sin(phi)  s (5c^2 - 5c + 1)
//        H12 = sqrt(7/(2 pi)) (20c^3 - 30c^2 + 12c - 1)
//  (2) hshGautron: Gautron et al.'s construction, the real spherical harmonics of the
//      hemisphere remapped onto the sphere by cos(theta') = 2 cos(theta) - 1:
//        K_l^m = sqrt((2l + 1) (l - |m|)! / (2 pi (l + |m|)!))
//        H_l^0 = K_l^0 P_l^0(2c - 1)
//        H_l^m = sqrt(2) K_l^m trig(|m| phi) P_l^|m|(2c - 1)      (m != 0)
//      with P_l^m the associated Legendre functions WITHOUT the Condon-Shortley phase
//      (P_1^1(x) = +sqrt(1 - x^2)). RTIViewer stores H_l^m at index k = l(l + 1) + m and uses
//      trig = cos for m < 0, sin for m > 0; its sign differs from the bare construction for
//      k = 4, 8, 10, 14 (it writes (c^2 - c) where the construction gives (c - c^2)). A basis
//      function's sign is a convention, but a file's coefficients are only right for the
//      viewer's convention, so the table's signs are the reference.
#pragma once

#include <algorithm>
#include <array>
#include <cmath>

namespace surrogate::reference {

constexpr double kPi = 3.141592653589793238462643383279502884;
// relight's clamp of the light's polar angle (RTIViewer's renderer uses 1.52 rad).
constexpr double kMaxTheta = kPi / 2 - 0.01;

// PTM term k (0..5) at the light's projection (lu, lv).
inline double ptmTerm(int k, double lu, double lv) {
  switch (k) {
    case 0: return lu * lu;
    case 1: return lv * lv;
    case 2: return lu * lv;
    case 3: return lu;
    case 4: return lv;
    case 5: return 1.0;
  }
  return NAN;
}

// The PTM arguments of a light vector: the projection of the unit vector, no division by lz.
inline std::array<double, 2> ptmArguments(double lx, double ly, double lz) {
  const double n = std::sqrt(lx * lx + ly * ly + lz * lz);
  return {lx / n, ly / n};
}

struct Angles {
  double theta, phi;
};

inline Angles hshAngles(double lx, double ly, double lz) {
  const double n = std::sqrt(lx * lx + ly * ly + lz * lz);
  const double theta = std::acos(std::max(-1.0, std::min(1.0, lz / n)));
  return {std::min(theta, kMaxTheta), std::atan2(ly, lx)};
}

// (1) RTIViewer's table, H0..H15.
inline double hshTable(int k, double theta, double phi) {
  const double pi = kPi;
  const double c = std::cos(theta);
  const double s = std::sqrt(c - c * c);
  const double t = 2 * c - 1;
  switch (k) {
    case 0: return 1 / std::sqrt(2 * pi);
    case 1: return std::sqrt(6 / pi) * std::cos(phi) * s;
    case 2: return std::sqrt(3 / (2 * pi)) * t;
    case 3: return std::sqrt(6 / pi) * std::sin(phi) * s;
    case 4: return std::sqrt(30 / pi) * std::cos(2 * phi) * (c * c - c);
    case 5: return std::sqrt(30 / pi) * std::cos(phi) * t * s;
    case 6: return std::sqrt(5 / (2 * pi)) * (6 * c * c - 6 * c + 1);
    case 7: return std::sqrt(30 / pi) * std::sin(phi) * t * s;
    case 8: return std::sqrt(30 / pi) * std::sin(2 * phi) * (c * c - c);
    case 9: return 2 * std::sqrt(35 / pi) * std::cos(3 * phi) * std::pow(c - c * c, 1.5);
    case 10: return std::sqrt(210 / pi) * std::cos(2 * phi) * t * (c * c - c);
    case 11: return 2 * std::sqrt(21 / pi) * std::cos(phi) * s * (5 * c * c - 5 * c + 1);
    case 12: return std::sqrt(7 / (2 * pi)) * (20 * c * c * c - 30 * c * c + 12 * c - 1);
    case 13: return 2 * std::sqrt(21 / pi) * std::sin(phi) * s * (5 * c * c - 5 * c + 1);
    case 14: return std::sqrt(210 / pi) * std::sin(2 * phi) * t * (c * c - c);
    case 15: return 2 * std::sqrt(35 / pi) * std::sin(3 * phi) * std::pow(c - c * c, 1.5);
  }
  return NAN;
}

// Associated Legendre function P_l^m(x), 0 <= m <= l, without the Condon-Shortley phase, by
// the standard recurrences: P_m^m = (2m - 1)!! (1 - x^2)^(m/2), P_(m+1)^m = x (2m + 1) P_m^m,
// (l - m) P_l^m = (2l - 1) x P_(l-1)^m - (l + m - 1) P_(l-2)^m.
inline double legendre(int l, int m, double x) {
  double pmm = 1;
  const double root = std::sqrt(std::max(0.0, 1 - x * x));
  for (int i = 1; i <= m; ++i) pmm *= (2 * i - 1) * root;
  if (l == m) return pmm;
  double pm1 = x * (2 * m + 1) * pmm;
  for (int ll = m + 2; ll <= l; ++ll) {
    const double next = ((2 * ll - 1) * x * pm1 - (ll + m - 1) * pmm) / (ll - m);
    pmm = pm1;
    pm1 = next;
  }
  return pm1;
}

inline double factorial(int n) {
  double f = 1;
  for (int i = 2; i <= n; ++i) f *= i;
  return f;
}

// (2) Gautron et al.'s construction with RTIViewer's index, trig and sign convention.
inline double hshGautron(int k, double theta, double phi) {
  int l = 0;
  while ((l + 1) * (l + 1) <= k) ++l;
  const int m = k - l * (l + 1);
  const int am = std::abs(m);
  const double norm =
      std::sqrt((2 * l + 1) * factorial(l - am) / (2 * kPi * factorial(l + am)));
  const double p = legendre(l, am, 2 * std::cos(theta) - 1);
  const double sign = (k == 4 || k == 8 || k == 10 || k == 14) ? -1.0 : 1.0;
  if (m == 0) return sign * norm * p;
  const double trig = m < 0 ? std::cos(am * phi) : std::sin(am * phi);
  return sign * std::sqrt(2.0) * norm * trig * p;
}

// H_k of a light vector (normalised and clamped here), from the table.
inline double hshTerm(int k, double lx, double ly, double lz) {
  const Angles a = hshAngles(lx, ly, lz);
  return hshTable(k, a.theta, a.phi);
}

}  // namespace surrogate::reference
