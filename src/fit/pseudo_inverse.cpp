#include "fit/pseudo_inverse.h"

#include <Eigen/SVD>

namespace surrogate::fit {

PseudoInverse pseudoInverse(const std::vector<double>& a, int rows, int cols) {
  using Matrix = Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor>;
  const Eigen::Map<const Matrix> A(a.data(), rows, cols);
  Eigen::JacobiSVD<Eigen::MatrixXd> svd(A, Eigen::ComputeThinU | Eigen::ComputeThinV);
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
  const Matrix p = svd.matrixV() * inverse.asDiagonal() * svd.matrixU().transpose();
  out.matrix.assign(p.data(), p.data() + p.size());
  return out;
}

}  // namespace surrogate::fit
