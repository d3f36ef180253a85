// Private to src/fit: the least-squares pseudo-inverse of a small design matrix.
//
//   A: N x T (one row per light, one column per basis term), row-major, double.
//   P = (A^T A)^-1 A^T  (T x N, row-major), so that the coefficients of one pixel are a = P s.
//
// Computed once per light set with Eigen's JacobiSVD (deterministic, and gives the
// minimum-norm solution when A is rank deficient, e.g. every light at the same elevation,
// where lu^2 + lv^2 is constant). Eigen stays inside the .cpp (docs/developer-guide.md,
// "Code conventions").
//
// dampedPseudoInverse is the Tikhonov-regularised form of fit/conditioning.h: with D the
// damped terms and n_k = |A e_k| the norm of term k's column (its size at the captured lights),
//
//   minimise |A a - s|^2 + mu sum_{k in D} n_k^2 a_k^2,   P = (A^T A + mu N_D)^-1 A^T,
//
// computed as the first N columns of the pseudo-inverse of A with one row sqrt(mu) n_k e_k
// appended per damped term (no normal equations, so no squared condition number).
#pragma once

#include <vector>

namespace surrogate::fit {

struct PseudoInverse {
  std::vector<double> matrix;  // T x N, row-major
  int rank = 0;                // numerical rank of A (T when well posed)
  std::vector<double> singularValues;  // of A, largest first (of the appended matrix when damped)
};

PseudoInverse pseudoInverse(const std::vector<double>& a, int rows, int cols);

// `damped`: term indices; mu >= 0 (mu = 0 gives pseudoInverse's matrix, not necessarily its bits).
PseudoInverse dampedPseudoInverse(const std::vector<double>& a, int rows, int cols,
                                  const std::vector<int>& damped, double mu);

}  // namespace surrogate::fit
