// Private to src/fit: the least-squares pseudo-inverse of a small design matrix.
//
//   A: N x T (one row per light, one column per basis term), row-major, double.
//   P = (A^T A)^-1 A^T  (T x N, row-major), so that the coefficients of one pixel are a = P s.
//
// Computed once per light set with Eigen's JacobiSVD (deterministic, and gives the
// minimum-norm solution when A is rank deficient, e.g. every light at the same elevation,
// where lu^2 + lv^2 is constant). Eigen stays inside the .cpp (docs/developer-guide.md,
// "Code conventions").
#pragma once

#include <vector>

namespace surrogate::fit {

struct PseudoInverse {
  std::vector<double> matrix;  // T x N, row-major
  int rank = 0;                // numerical rank of A (T when well posed)
};

PseudoInverse pseudoInverse(const std::vector<double>& a, int rows, int cols);

}  // namespace surrogate::fit
