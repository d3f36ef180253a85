// The PTM polynomial of one texel: evaluation, its maximum, and the diffuse gain transform
// (docs/hrti-math.md, "Normals from a PTM" and "Diffuse gain", corrected formulas).
//
//     L(lu, lv) = a0 lu^2 + a1 lv^2 + a2 lu lv + a3 lu + a4 lv + a5
//     maximum:  d = 4 a0 a1 - a2^2,
//               lu0 = (a2 a4 - 2 a1 a3) / d,  lv0 = (a2 a3 - 2 a0 a4) / d
//               (a maximum when d > 0 and a0 < 0)
//     gain g:   a0' = g a0,  a1' = g a1,  a2' = g a2
//               a3' = (1 - g)(2 a0 lu0 + a2 lv0) + a3
//               a4' = (1 - g)(2 a1 lv0 + a2 lu0) + a4
//               a5' = (1 - g)(a0 lu0^2 + a1 lv0^2 + a2 lu0 lv0) + (a3 - a3') lu0
//                     + (a4 - a4') lv0 + a5
// The gain keeps L's value and gradient at (lu0, lv0) for ANY pivot, so at a maximum it keeps
// the maximum's position and value while multiplying the curvature by g.
//
//   PtmCoefficients a = {-40, -40, 0, 10, 5, 200};
//   double lu0, lv0;
//   if (ptmMaximum(a, &lu0, &lv0)) a = applyDiffuseGain(a, 3.0, lu0, lv0);
#pragma once

#include <array>

namespace surrogate::fit {

using PtmCoefficients = std::array<double, 6>;  // a0..a5, 0..255 units

double evaluatePtm(const PtmCoefficients& a, double lu, double lv);

// Sets (*lu0, *lv0) to the stationary point when d != 0 (else to 0, 0); returns true when it
// is a maximum (d > 0 and a0 < 0). The point is not clamped to the unit disc.
bool ptmMaximum(const PtmCoefficients& a, double* lu0, double* lv0);

PtmCoefficients applyDiffuseGain(const PtmCoefficients& a, double g, double lu0, double lv0);

}  // namespace surrogate::fit
