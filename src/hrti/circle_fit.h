// Least-squares circle through edge points: algebraic (Kasa) start, then geometric
// Gauss-Newton on the distances |p - c| - r, with outlier rejection.
#pragma once

#include <vector>

namespace surrogate::hrti {

struct Point2 {
  double x, y;
};

struct CircleFit {
  double cx = 0, cy = 0, r = 0;
  int inliers = 0;
  bool ok = false;
  // The Gauss-Newton covariance of (cx, cy, r) at the solution, s^2 (J^T J)^-1 with s^2 the
  // inliers' residual variance (n - 3 degrees of freedom): the standard errors (pixels) if the
  // points' errors were independent. 0 with fewer than 4 inliers.
  double sigmaCx = 0, sigmaCy = 0, sigmaR = 0;
  double residualSd = 0;  // s, pixels
};

// `outlierPixels`: points farther than this from the circle (and than 3 robust sigmas) are
// dropped and the fit repeated.
CircleFit fitCircle(const std::vector<Point2>& points, double outlierPixels);

}  // namespace surrogate::hrti
