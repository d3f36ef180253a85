// Fitting bases: which functions of the light direction a per-pixel model is made of.
//
//   PTM (6 terms), (lu, lv) = (lx, ly), the light's projection on the image plane:
//       w = (lu^2, lv^2, lu*lv, lu, lv, 1)
//   HSH (hemispherical harmonics, 4 = order 2, 9 = order 3, 16 = order 4 terms):
//       theta = min(acos(lz), pi/2 - 0.01), phi = atan2(ly, lx),
//       c = cos(theta), s = sqrt(c - c^2), t = 2c - 1,
//       H0 = 1/sqrt(2 pi), H1 = sqrt(6/pi) cos(phi) s, H2 = sqrt(3/(2 pi)) t, ...
//   (docs/hrti-math.md, "The HSH basis", term by term; light vectors are normalised first.)
//
//   Basis b = parseBasis("hsh3");           // Basis::Hsh3, basisTerms(b) == 9
//   double w[9];
//   hshBasis(0.3, 0.4, 0.866, 9, w);        // the row of the fitting matrix for that light
#pragma once

#include <array>
#include <string>

namespace surrogate::fit {

enum class Basis {
  PtmLrgb,  // "ptm-lrgb": luminance polynomial + per-pixel colour (.ptm PTM_FORMAT_LRGB)
  PtmRgb,   // "ptm-rgb":  one polynomial per colour channel (.ptm PTM_FORMAT_RGB)
  Hsh2,     // "hsh2":     HSH order 2, 4 terms per channel (.rti)
  Hsh3,     // "hsh3":     HSH order 3, 9 terms per channel (.rti)
};

const char* basisName(Basis basis);
// Throws Error(Usage) naming "--basis" for anything but the four names above.
Basis parseBasis(const std::string& name);
bool isPtm(Basis basis);
int basisTerms(Basis basis);  // coefficients per channel: 6, 6, 4, 9

// The HSH elevation clamp of relight's renderer: theta <= pi/2 - 0.01.
constexpr double kHshMaxTheta = 1.5607963267948966;

std::array<double, 6> ptmBasis(double lu, double lv);

// HSH terms H0..H(terms-1) at the direction (lx, ly, lz) (normalised here; theta clamped).
// `terms` is 1, 4, 9 or 16.
void hshBasis(double lx, double ly, double lz, int terms, double* out);

}  // namespace surrogate::fit
