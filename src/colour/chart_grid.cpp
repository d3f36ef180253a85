// The patch grid's geometry and its refinement on the image. See chart_grid.h.
//
// Why edges: mcc's box is a rough fit of its own chart model; the patches' borders with the
// black gaps are the sharpest, most numerous features of the chart (24 x 4 edges), so the place
// where the signed brightness fall across every predicted edge is largest is the chart's place
// to a fraction of a pixel. Blurring first widens the basin (coarse scales pull from ~10 px away).
#include "colour/chart_grid.h"

#include <algorithm>
#include <cmath>

#include <opencv2/imgproc.hpp>

namespace surrogate::colour {

Point Homography::map(double u, double v) const {
  const double w = m[2][0] * u + m[2][1] * v + m[2][2];
  return {(m[0][0] * u + m[0][1] * v + m[0][2]) / w, (m[1][0] * u + m[1][1] * v + m[1][2]) / w};
}

Homography Homography::inverse() const {
  Homography r;
  const auto& a = m;
  r.m[0][0] = a[1][1] * a[2][2] - a[1][2] * a[2][1];
  r.m[0][1] = a[0][2] * a[2][1] - a[0][1] * a[2][2];
  r.m[0][2] = a[0][1] * a[1][2] - a[0][2] * a[1][1];
  r.m[1][0] = a[1][2] * a[2][0] - a[1][0] * a[2][2];
  r.m[1][1] = a[0][0] * a[2][2] - a[0][2] * a[2][0];
  r.m[1][2] = a[0][2] * a[1][0] - a[0][0] * a[1][2];
  r.m[2][0] = a[1][0] * a[2][1] - a[1][1] * a[2][0];
  r.m[2][1] = a[0][1] * a[2][0] - a[0][0] * a[2][1];
  r.m[2][2] = a[0][0] * a[1][1] - a[0][1] * a[1][0];
  return r;  // the adjugate: a homography is defined up to scale
}

Homography homography(const std::array<Point, 4>& c) {
  const double x0 = c[0][0], y0 = c[0][1], x1 = c[1][0], y1 = c[1][1];
  const double x2 = c[2][0], y2 = c[2][1], x3 = c[3][0], y3 = c[3][1];
  const double sx = x0 - x1 + x2 - x3, sy = y0 - y1 + y2 - y3;
  const double dx1 = x1 - x2, dx2 = x3 - x2, dy1 = y1 - y2, dy2 = y3 - y2;
  const double den = dx1 * dy2 - dx2 * dy1;
  const double g = den != 0 ? (sx * dy2 - dx2 * sy) / den : 0;
  const double h = den != 0 ? (dx1 * sy - sx * dy1) / den : 0;
  Homography r;
  r.m[0][0] = x1 - x0 + g * x1;
  r.m[0][1] = x3 - x0 + h * x3;
  r.m[0][2] = x0;
  r.m[1][0] = y1 - y0 + g * y1;
  r.m[1][1] = y3 - y0 + h * y3;
  r.m[1][2] = y0;
  r.m[2][0] = g;
  r.m[2][1] = h;
  r.m[2][2] = 1;
  return r;
}

UnitRect patchRect(int k, double gap) {
  const int c = k % kChartColumns, r = k / kChartColumns;
  const double pu = 1.0 / (kChartColumns - gap), pv = 1.0 / (kChartRows - gap);
  return {c * pu, (c + 1 - gap) * pu, r * pv, (r + 1 - gap) * pv};
}

UnitRect centralRect(int k, double gap, double half) {
  const UnitRect p = patchRect(k, gap);
  const double pu = 1.0 / (kChartColumns - gap), pv = 1.0 / (kChartRows - gap);
  const double uc = (p.u0 + p.u1) / 2, vc = (p.v0 + p.v1) / 2;
  return {uc - half * pu, uc + half * pu, vc - half * pv, vc + half * pv};
}

namespace {

double distance(const Point& a, const Point& b) { return std::hypot(a[0] - b[0], a[1] - b[1]); }

}  // namespace

double patchSideOf(const Grid& grid) {
  const Homography h = homography(grid.corners);
  double sum = 0;
  for (int k = 0; k < kChartPatches; ++k) {
    const UnitRect p = patchRect(k, grid.gap);
    const Point a = h.map(p.u0, p.v0), b = h.map(p.u1, p.v0), c = h.map(p.u1, p.v1),
                d = h.map(p.u0, p.v1);
    sum += (distance(a, b) + distance(b, c) + distance(c, d) + distance(d, a)) / 4;
  }
  return sum / kChartPatches;
}

double gapFromPatchSide(const std::array<Point, 4>& c, double patchSide) {
  if (patchSide <= 0) return kDefaultGap;
  // A side of n patches and n - 1 gaps: side / patch = (n - gap) / (1 - gap).
  const double width = (distance(c[0], c[1]) + distance(c[3], c[2])) / 2;
  const double height = (distance(c[0], c[3]) + distance(c[1], c[2])) / 2;
  const double rw = patchSide / width, rh = patchSide / height;
  const double gw = (1 - kChartColumns * rw) / (1 - rw), gh = (1 - kChartRows * rh) / (1 - rh);
  return std::clamp((gw + gh) / 2, 0.0, 0.5);
}

namespace {

float bilinear(const cv::Mat& m, double x, double y) {
  if (!(x >= 0 && y >= 0 && x < m.cols - 1 && y < m.rows - 1)) return 0;
  const int ix = static_cast<int>(x), iy = static_cast<int>(y);
  const double fx = x - ix, fy = y - iy;
  const float* r0 = m.ptr<float>(iy);
  const float* r1 = m.ptr<float>(iy + 1);
  return static_cast<float>((1 - fy) * ((1 - fx) * r0[ix] + fx * r0[ix + 1]) +
                            fy * ((1 - fx) * r1[ix] + fx * r1[ix + 1]));
}

// The sum, over every patch edge, of the brightness fall from the patch outwards.
double edgeScore(const cv::Mat& gx, const cv::Mat& gy, const Grid& grid) {
  constexpr int kSamples = 12;
  const Homography h = homography(grid.corners);
  double total = 0;
  for (int k = 0; k < kChartPatches; ++k) {
    const UnitRect p = patchRect(k, grid.gap);
    const double du = (p.u1 - p.u0) * 0.02, dv = (p.v1 - p.v0) * 0.02;
    for (int e = 0; e < 4; ++e) {
      for (int i = 0; i < kSamples; ++i) {
        const double t = 0.08 + 0.84 * (i + 0.5) / kSamples;
        double u, v, ou, ov;  // a point on the edge and its outward direction in the unit square
        if (e == 0) u = p.u0 + t * (p.u1 - p.u0), v = p.v0, ou = 0, ov = -dv;
        else if (e == 1) u = p.u1, v = p.v0 + t * (p.v1 - p.v0), ou = du, ov = 0;
        else if (e == 2) u = p.u0 + t * (p.u1 - p.u0), v = p.v1, ou = 0, ov = dv;
        else u = p.u0, v = p.v0 + t * (p.v1 - p.v0), ou = -du, ov = 0;
        const Point a = h.map(u, v), o = h.map(u + ou, v + ov);
        const Point along = h.map(u + (ov != 0 ? du : 0), v + (ou != 0 ? dv : 0));
        double nx = -(along[1] - a[1]), ny = along[0] - a[0];
        if (nx * (o[0] - a[0]) + ny * (o[1] - a[1]) < 0) nx = -nx, ny = -ny;
        const double len = std::hypot(nx, ny);
        if (len == 0) continue;
        total -= (bilinear(gx, a[0], a[1]) * nx + bilinear(gy, a[0], a[1]) * ny) / len;
      }
    }
  }
  return total;
}

// One move of the pattern search: direction d scaled by `step` pixels.
Grid moved(const Grid& g, int d, double step, double pitch) {
  Grid r = g;
  if (d < 8) {
    r.corners[d / 2][d % 2] += step;
    return r;
  }
  double cx = 0, cy = 0;
  for (const Point& p : g.corners) cx += p[0] / 4, cy += p[1] / 4;
  const double radius = std::max(1.0, distance(g.corners[0], g.corners[2]) / 2);
  for (Point& p : r.corners) {
    const double x = p[0] - cx, y = p[1] - cy;
    if (d == 8) p[0] += step;
    if (d == 9) p[1] += step;
    if (d == 10) p[0] = cx + x * (1 + step / radius), p[1] = cy + y * (1 + step / radius);
    if (d == 11) {
      const double a = step / radius, c = std::cos(a), s = std::sin(a);
      p[0] = cx + c * x - s * y, p[1] = cy + s * x + c * y;
    }
  }
  if (d == 12) r.gap = std::clamp(g.gap + step / pitch, 0.02, 0.45);
  return r;
}

}  // namespace

Grid refineGrid(const cv::Mat& grey, Grid grid, const std::vector<double>& sigmas) {
  constexpr int kDirections = 13;
  constexpr int kMaxEvaluations = 3000;
  for (double sigma : sigmas) {
    cv::Mat blurred, gx, gy;
    cv::GaussianBlur(grey, blurred, cv::Size(0, 0), sigma, sigma, cv::BORDER_REPLICATE);
    cv::Sobel(blurred, gx, CV_32F, 1, 0, 3, 0.125, 0, cv::BORDER_REPLICATE);
    cv::Sobel(blurred, gy, CV_32F, 0, 1, 3, 0.125, 0, cv::BORDER_REPLICATE);
    const double pitch = std::max(1.0, patchSideOf(grid) / (1 - grid.gap));
    double best = edgeScore(gx, gy, grid);
    double step = sigma;
    const double finest = std::min(0.05, sigma / 16);
    int evaluations = 0;
    while (step >= finest && evaluations < kMaxEvaluations) {
      bool improved = false;
      for (int d = 0; d < kDirections; ++d) {
        for (double sign : {1.0, -1.0}) {
          const Grid candidate = moved(grid, d, sign * step, pitch);
          const double score = edgeScore(gx, gy, candidate);
          ++evaluations;
          if (score > best) {
            best = score, grid = candidate, improved = true;
            break;
          }
        }
      }
      if (!improved) step /= 2;
    }
  }
  return grid;
}

}  // namespace surrogate::colour
