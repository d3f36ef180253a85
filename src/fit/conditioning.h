// Private to src/fit: a fit conditioned on its light set (docs/hrti-math.md, "Conditioning on
// the light set").
//
// Each coefficient plane is quantised to 8 bits over its own range (fit/quantise.h). When the
// lights leave some terms nearly indistinguishable (a narrow cone of lights around the view
// axis, where HSH order 3's five highest terms look alike at every captured light), least
// squares balances large coefficients of opposite signs; their ranges are large, the
// quantisation step of each plane with them, and the re-rendered model is far worse than the
// fit was. How much worse follows from the lights alone, through the NOISE GAIN of an inverse
// P (T x N) at the captured lights:
//
//     g_k = sum_i |P_ki|                       the range of coefficient k when each sample
//                                              ranges over [0, 1]
//     G   = sqrt( (1/N) sum_i sum_k A_ik^2 g_k^2 )
//
// Quantising plane k in steps of g_k / 255 and re-rendering at the N lights gives an RMS error
// G times that of rounding the photographs themselves to 8 bits (independent uniform errors).
// G is unchanged by scaling a term, and is 2 to 10 for lights spread over the hemisphere.
//
// When G <= kMaxNoiseGain the fit is plain least squares: the inverse is pseudoInverse's,
// the same bits as before conditioning existed, and the weight is exactly 0. Otherwise the
// basis's higher terms (HSH order 3's five order-3 terms, PTM's three quadratic terms) are
// damped toward the lower-order fit (dampedPseudoInverse, fit/pseudo_inverse.h) by the
// smallest weight mu of the ladder 2^j (j = -34..20) whose noise gain is at most
//
//     max(kMaxNoiseGain, kLowerOrderMargin * G_lower)
//
// where G_lower is the noise gain of the lower-order fit itself (the limit as mu grows: HSH
// order 2, or the PTM plane a3 lu + a4 lv + a5). Everything follows from the lights, so a
// re-execution chooses the same weight.
//
//   const Conditioning c = conditionedInverse(design, n, Basis::Hsh3);
//   // c.inverse.matrix is P; c.weight is 0 or mu; c.damped = {4, 5, 6, 7, 8} when mu > 0
#pragma once

#include <array>
#include <vector>

#include "fit/basis.h"
#include "fit/fit.h"
#include "fit/pseudo_inverse.h"

namespace surrogate::fit {

// Above this noise gain a fit is conditioned: 16 times the error of rounding the photographs
// to 8 bits. Lights spread over the hemisphere stay below 10 (HSH order 3 with 9 lights on a
// spiral from 20 to 80 degrees of elevation: 9.5); a 12-light cone 25-40 degrees wide around
// the view axis gives 900-1900 for HSH order 3.
constexpr double kMaxNoiseGain = 16.0;
// A conditioned fit may amplify quantisation up to this factor more than the lower-order fit
// does: one bit of each 8-bit plane. G bounds the ranges by samples that each take any value;
// photographs of one surface vary together, so the true ranges are a fraction of the bound.
// Measured on eight real 12-light sets (docs/hrti-math.md): 1.06 (0.5 dB) left HSH order 3
// 0.2-1.5 dB above order 2, 2 gave 0.6-4.1 dB, 3 less than 2 on half the sets.
constexpr double kLowerOrderMargin = 2.0;

struct Conditioning {
  PseudoInverse inverse;        // what the fit multiplies the samples by
  double conditionNumber = 0;   // sigma_max / sigma_min of the design (infinity when rank deficient)
  double noiseGain = 0;         // G of `inverse`
  double plainNoiseGain = 0;    // G of the plain least-squares inverse
  double weight = 0;            // mu; exactly 0 for plain least squares
  std::vector<int> damped;      // the terms mu penalises (empty when mu = 0)
};

// `design`: N x T, row-major, the basis at the (normalised) lights.
Conditioning conditionedInverse(const std::vector<double>& design, int n, Basis basis);

// G above, for the N x T design A and the T x N inverse P.
double noiseGain(const std::vector<double>& design, int n, int terms, const std::vector<double>& p);

// The terms conditioning damps: HSH order 3's {4..8}, PTM's quadratic {0, 1, 2}; none for HSH
// order 2, whose lower order is a constant.
std::vector<int> higherTerms(Basis basis);

// Copies the conditioning into `stats` (if not null), with the lights' spread.
void recordConditioning(const Conditioning& c, const std::vector<std::array<double, 3>>& lights,
                        FitStatistics* stats);

}  // namespace surrogate::fit
