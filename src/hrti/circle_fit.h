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
};

// `outlierPixels`: points farther than this from the circle (and than 3 robust sigmas) are
// dropped and the fit repeated.
CircleFit fitCircle(const std::vector<Point2>& points, double outlierPixels);

}  // namespace surrogate::hrti
