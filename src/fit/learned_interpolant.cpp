#include "fit/learned_interpolant.h"

#include <cmath>
#include <limits>

namespace surrogate::fit {

namespace {

double kernel(const std::array<double, 3>& a, const std::array<double, 3>& b, double width) {
  const double dx = a[0] - b[0], dy = a[1] - b[1], dz = a[2] - b[2];
  return std::exp(-(dx * dx + dy * dy + dz * dz) / (2 * width * width));
}

void trend(const std::array<double, 3>& l, int terms, double* out) {
  out[0] = 1;
  out[1] = l[0];
  out[2] = l[1];
  if (terms == 4) {
    out[3] = l[2];
  } else {
    out[3] = l[0] * l[0];
    out[4] = l[0] * l[1];
    out[5] = l[1] * l[1];
  }
}

// The (N + m) x N matrix taking the samples to [a; b].
Eigen::MatrixXd solveMatrix(const std::vector<std::array<double, 3>>& lights, double width, double ridge, int terms) {
  const int N = static_cast<int>(lights.size());
  Eigen::MatrixXd A = Eigen::MatrixXd::Zero(N + terms, N + terms);
  double phi[6];
  for (int i = 0; i < N; ++i) {
    for (int j = 0; j < N; ++j) A(i, j) = kernel(lights[i], lights[j], width);
    A(i, i) += ridge;
    trend(lights[i], terms, phi);
    for (int t = 0; t < terms; ++t) A(i, N + t) = A(N + t, i) = phi[t];
  }
  Eigen::MatrixXd rhs = Eigen::MatrixXd::Zero(N + terms, N);
  rhs.topRows(N).setIdentity();
  // The saddle-point system is symmetric indefinite and well scaled (kernel values 0..1, ridge
  // added): partial pivoting suffices.
  return A.partialPivLu().solve(rhs);
}

}  // namespace

Eigen::MatrixXd Interpolant::weightsAt(const std::vector<std::array<double, 3>>& directions) const {
  const int N = static_cast<int>(lights.size());
  Eigen::MatrixXd basis(directions.size(), N + trendTerms);
  double phi[6];
  for (std::size_t d = 0; d < directions.size(); ++d) {
    for (int i = 0; i < N; ++i) basis(d, i) = kernel(directions[d], lights[i], width);
    trend(directions[d], trendTerms, phi);
    for (int t = 0; t < trendTerms; ++t) basis(d, N + t) = phi[t];
  }
  return basis * solve;
}

Interpolant chooseInterpolant(const std::vector<std::array<double, 3>>& lights, const Eigen::MatrixXd& gram,
                              double samples, double width, double ridge) {
  const int N = static_cast<int>(lights.size());
  // Widths from a fifth of the closest spacing to the whole hemisphere; ridges from nearly
  // interpolating to strong smoothing. A dome's noise, a hand-held capture's errors in the light
  // directions and the surface's own sharpness decide which wins, per capture.
  const std::vector<double> widths = width > 0 ? std::vector<double>{width}
                                               : std::vector<double>{0.05, 0.07, 0.1, 0.14, 0.2, 0.28, 0.4, 0.56, 0.8};
  const std::vector<double> ridges = ridge > 0 ? std::vector<double>{ridge}
                                               : std::vector<double>{1e-5, 1e-4, 1e-3, 3e-3, 1e-2, 3e-2, 0.1, 0.3};
  std::vector<int> trends = {4};
  if (N >= 16) trends.push_back(6);
  Interpolant best;
  best.leaveOneOutMse = std::numeric_limits<double>::infinity();
  best.lights = lights;
  for (int terms : trends)
    for (double h : widths)
      for (double lambda : ridges) {
        Eigen::MatrixXd solve = solveMatrix(lights, h, lambda, terms);
        Interpolant candidate;
        candidate.lights = lights;
        candidate.width = h;
        candidate.ridge = lambda;
        candidate.trendTerms = terms;
        candidate.solve = std::move(solve);
        const Eigen::MatrixXd S = candidate.weightsAt(lights);  // N x N hat matrix
        Eigen::MatrixXd R = Eigen::MatrixXd::Identity(N, N) - S;
        bool usable = true;
        for (int i = 0; i < N; ++i) {
          const double leverage = 1.0 - S(i, i);
          if (!(leverage > 1e-9)) usable = false;  // interpolates that photograph exactly: no estimate
          else R.row(i) /= leverage;
        }
        if (!usable) continue;
        const double mse = (R * gram * R.transpose()).trace() / (samples * N);
        if (mse < best.leaveOneOutMse) {
          best = std::move(candidate);
          best.leaveOneOutMse = mse;
        }
      }
  return best;
}

}  // namespace surrogate::fit
