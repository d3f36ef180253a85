#include "fit/pseudo_inverse.h"

#include <cmath>

#include <Eigen/SVD>

namespace surrogate::fit {

namespace {
using Matrix = Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor>;

// V S^+ U^T of `m`, its leading `keep` columns (the rows of A, without appended rows).
PseudoInverse invert(const Eigen::MatrixXd& m, Eigen::Index keep) {
  Eigen::JacobiSVD<Eigen::MatrixXd> svd(m, Eigen::ComputeThinU | Eigen::ComputeThinV);
  const Eigen::VectorXd& sigma = svd.singularValues();
  // Singular values below this relative threshold are treated as zero (rank deficiency).
  const double threshold = sigma.size() ? sigma(0) * 1e-10 : 0.0;
  Eigen::VectorXd inverse = Eigen::VectorXd::Zero(sigma.size());
  PseudoInverse out;
  for (Eigen::Index i = 0; i < sigma.size(); ++i) {
    if (sigma(i) > threshold) {
      inverse(i) = 1.0 / sigma(i);
      ++out.rank;
    }
  }
  out.singularValues.assign(sigma.data(), sigma.data() + sigma.size());
  const Eigen::MatrixXd u = svd.matrixU().topRows(keep);  // as a plain matrix: the product below
                                                          // is the one plain least squares always made
  const Matrix p = svd.matrixV() * inverse.asDiagonal() * u.transpose();
  out.matrix.assign(p.data(), p.data() + p.size());
  return out;
}
}  // namespace

PseudoInverse pseudoInverse(const std::vector<double>& a, int rows, int cols) {
  const Eigen::Map<const Matrix> A(a.data(), rows, cols);
  return invert(A, rows);
}

PseudoInverse dampedPseudoInverse(const std::vector<double>& a, int rows, int cols,
                                  const std::vector<int>& damped, double mu) {
  const Eigen::Map<const Matrix> A(a.data(), rows, cols);
  Eigen::MatrixXd m = Eigen::MatrixXd::Zero(rows + static_cast<Eigen::Index>(damped.size()), cols);
  m.topRows(rows) = A;
  for (std::size_t d = 0; d < damped.size(); ++d)
    m(rows + static_cast<Eigen::Index>(d), damped[d]) = std::sqrt(mu) * A.col(damped[d]).norm();
  return invert(m, rows);
}

}  // namespace surrogate::fit
