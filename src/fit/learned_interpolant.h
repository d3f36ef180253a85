// Private to src/fit: step 1 of a learned fit (fit/learned.h), a texel's response at any light
// from its N photographs, and the choice of its smoothness by leaving each photograph out.
//
// The response is kriging with a trend (kernel ridge regression plus an unpenalised low-order
// polynomial in the light):
//
//     f(l) = k(l)^T a + phi(l)^T b,   [K + lambda I, Phi; Phi^T, 0] [a; b] = [s; 0]
//     k_i(l) = exp(-|l - l_i|^2 / (2 h^2)),   phi = (1, lx, ly, lz) or (1, lx, ly, lx^2, lx ly, ly^2)
//
// so f is linear in the samples s: f(l) = t(l)^T s. The fitted values at the captured lights are
// S s; for such penalised least squares the value at light i with photograph i left out differs
// from s_i by (s_i - (S s)_i) / (1 - S_ii), exactly, so the leave-one-out error over many texels
// is trace(D (I - S) G (I - S)^T D) / (N texels), D = diag(1 / (1 - S_ii)), G the sum of s s^T:
// one N x N matrix for the whole image, whatever the number of candidates tried.
#pragma once

#include <array>
#include <vector>

#include <Eigen/Dense>

namespace surrogate::fit {

struct Interpolant {
  double width = 0;   // h, in units of the distance between unit vectors (~ radians when small)
  double ridge = 0;   // lambda, relative to the kernel's diagonal (1)
  int trendTerms = 0; // 4 (linear) or 6 (PTM's quadratic)
  double leaveOneOutMse = 0;  // per sample, in squared 0..1 units
  std::vector<std::array<double, 3>> lights;
  Eigen::MatrixXd solve;  // (N + trend) x N: [a; b] = solve * s

  // |directions| x N: row j is t(direction j)^T.
  Eigen::MatrixXd weightsAt(const std::vector<std::array<double, 3>>& directions) const;
};

// `gram` = sum over the sampled texels and channels of s s^T (N x N), `samples` their number
// (texels x channels). A width/ridge > 0 is taken as given; 0 is chosen among candidates by the
// leave-one-out error (ties to the first candidate: deterministic).
Interpolant chooseInterpolant(const std::vector<std::array<double, 3>>& lights, const Eigen::MatrixXd& gram,
                              double samples, double width, double ridge);

}  // namespace surrogate::fit
