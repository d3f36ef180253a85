#include "hrti/circle_fit.h"

#include <Eigen/Dense>

#include <algorithm>
#include <cmath>

namespace surrogate::hrti {

namespace {

CircleFit algebraic(const std::vector<Point2>& p) {
  CircleFit fit;
  if (p.size() < 3) return fit;
  Eigen::MatrixXd a(p.size(), 3);
  Eigen::VectorXd b(p.size());
  for (std::size_t i = 0; i < p.size(); ++i) {
    a(i, 0) = p[i].x;
    a(i, 1) = p[i].y;
    a(i, 2) = 1;
    b(i) = -(p[i].x * p[i].x + p[i].y * p[i].y);
  }
  const Eigen::Vector3d s = a.colPivHouseholderQr().solve(b);
  fit.cx = -s(0) / 2;
  fit.cy = -s(1) / 2;
  const double r2 = fit.cx * fit.cx + fit.cy * fit.cy - s(2);
  if (!(r2 > 0)) return fit;
  fit.r = std::sqrt(r2);
  fit.ok = true;
  fit.inliers = static_cast<int>(p.size());
  return fit;
}

void geometric(const std::vector<Point2>& p, CircleFit& fit) {
  for (int iteration = 0; iteration < 20; ++iteration) {
    Eigen::MatrixXd j(p.size(), 3);
    Eigen::VectorXd res(p.size());
    for (std::size_t i = 0; i < p.size(); ++i) {
      const double dx = p[i].x - fit.cx, dy = p[i].y - fit.cy, d = std::hypot(dx, dy);
      if (d < 1e-12) continue;
      j(i, 0) = -dx / d;
      j(i, 1) = -dy / d;
      j(i, 2) = -1;
      res(i) = d - fit.r;
    }
    const Eigen::Vector3d step = j.colPivHouseholderQr().solve(-res);
    fit.cx += step(0);
    fit.cy += step(1);
    fit.r += step(2);
    if (step.norm() < 1e-9) break;
  }
}

// The standard errors from the residuals at the solution: s^2 (J^T J)^-1.
void covariance(const std::vector<Point2>& p, CircleFit& fit) {
  if (p.size() < 4) return;
  Eigen::Matrix3d jtj = Eigen::Matrix3d::Zero();
  double sum2 = 0;
  for (const Point2& q : p) {
    const double dx = q.x - fit.cx, dy = q.y - fit.cy, d = std::hypot(dx, dy);
    if (d < 1e-12) continue;
    const Eigen::Vector3d row(-dx / d, -dy / d, -1);
    jtj += row * row.transpose();
    sum2 += (d - fit.r) * (d - fit.r);
  }
  const double s2 = sum2 / double(p.size() - 3);
  const Eigen::FullPivLU<Eigen::Matrix3d> lu(jtj);
  if (!lu.isInvertible()) return;
  const Eigen::Matrix3d cov = s2 * lu.inverse();
  fit.sigmaCx = std::sqrt(std::max(0.0, cov(0, 0)));
  fit.sigmaCy = std::sqrt(std::max(0.0, cov(1, 1)));
  fit.sigmaR = std::sqrt(std::max(0.0, cov(2, 2)));
  fit.residualSd = std::sqrt(s2);
}

}  // namespace

CircleFit fitCircle(const std::vector<Point2>& points, double outlierPixels) {
  std::vector<Point2> kept = points;
  CircleFit fit;
  for (int round = 0; round < 3; ++round) {
    fit = algebraic(kept);
    if (!fit.ok) return fit;
    geometric(kept, fit);
    std::vector<double> residuals;
    for (const Point2& q : kept) residuals.push_back(std::abs(std::hypot(q.x - fit.cx, q.y - fit.cy) - fit.r));
    std::vector<double> sorted = residuals;
    std::nth_element(sorted.begin(), sorted.begin() + sorted.size() / 2, sorted.end());
    const double limit = std::max(outlierPixels, 3 * 1.4826 * sorted[sorted.size() / 2]);
    std::vector<Point2> next;
    for (std::size_t i = 0; i < kept.size(); ++i)
      if (residuals[i] <= limit) next.push_back(kept[i]);
    if (next.size() == kept.size() || next.size() < 3) break;
    kept = std::move(next);
  }
  fit.inliers = static_cast<int>(kept.size());
  covariance(kept, fit);
  return fit;
}

}  // namespace surrogate::hrti
