#include "stages/frame_checks.h"

#include <algorithm>
#include <cmath>
#include <sstream>

namespace surrogate::stages {

namespace {

// A number as a person wrote it: "45", "57.5", "-5".
std::string num(double v) {
  std::ostringstream s;
  s.precision(10);
  s << v;
  return s.str();
}

std::string frameText(int width, int height) {
  return std::to_string(width) + "x" + std::to_string(height) + " frame";
}

}  // namespace

std::string sphereCircleProblem(double cx, double cy, double r, int width, int height) {
  if (!std::isfinite(cx) || !std::isfinite(cy) || !std::isfinite(r))
    return "CX, CY and R must be finite numbers (pixels)";
  if (r <= 0) return "the radius R is " + num(r) + "; it must be above 0";
  if (r < kMinSphereRadius)
    return "the radius R is " + num(r) + " pixels; a sphere needs a radius of at least " +
           num(kMinSphereRadius) + " pixels to show a highlight inside its rim";
  if (cx < 0 || cy < 0)
    return "the centre (" + num(cx) + ", " + num(cy) + ") has a negative coordinate; pixel "
           "coordinates start at 0 at the top-left pixel";
  if (width <= 0 || height <= 0) return "";
  if (cx > width - 1 || cy > height - 1)
    return "the centre (" + num(cx) + ", " + num(cy) + ") is outside the " + frameText(width, height) +
           ": CX must be from 0 to " + std::to_string(width - 1) + " and CY from 0 to " +
           std::to_string(height - 1);
  const double largest = std::min(width, height) / 2.0;
  if (r <= largest) return "";
  const double inside = discShareInFrame(cx, cy, r, width, height);
  if (inside >= kMinDiscShareInFrame) return "";
  return "the radius R is " + num(r) + " pixels, more than half the smaller side of the " +
         frameText(width, height) + " (" + num(largest) + " pixels), and only " +
         std::to_string(static_cast<int>(std::floor(inside * 100))) +
         " % of its disc is inside the frame: a sphere that size cannot be in the images (a sphere "
         "cut by the frame's edge needs at least half of its disc inside it)";
}

double discShareInFrame(double cx, double cy, double r, int width, int height) {
  if (!(r > 0) || width <= 0 || height <= 0) return 0;
  // Column by column (midpoint rule over 4096 strips): the chord of the disc at each x, clipped
  // to the frame's rows; the frame covers -0.5 to width - 0.5 (pixel centres at whole numbers).
  constexpr int kStrips = 4096;
  double area = 0;
  const double step = 2 * r / kStrips;
  for (int i = 0; i < kStrips; ++i) {
    const double x = cx - r + (i + 0.5) * step;
    if (x < -0.5 || x > width - 0.5) continue;
    const double half = std::sqrt(std::max(0.0, r * r - (x - cx) * (x - cx)));
    const double top = std::max(cy - half, -0.5), bottom = std::min(cy + half, height - 0.5);
    if (bottom > top) area += (bottom - top) * step;
  }
  return area / (M_PI * r * r);
}

std::string highlightPointProblem(double x, double y, int width, int height,
                                  const std::optional<SphereCircle>& sphere) {
  if (!std::isfinite(x) || !std::isfinite(y)) return "X and Y must be finite numbers (pixels)";
  if (x < 0 || y < 0)
    return "the point (" + num(x) + ", " + num(y) + ") has a negative coordinate; pixel "
           "coordinates start at 0 at the top-left pixel";
  if (width > 0 && height > 0 && (x > width - 1 || y > height - 1))
    return "the point (" + num(x) + ", " + num(y) + ") is outside the " + frameText(width, height) +
           ": X must be from 0 to " + std::to_string(width - 1) + " and Y from 0 to " +
           std::to_string(height - 1);
  if (sphere) {
    const double d = std::hypot(x - sphere->cx, y - sphere->cy);
    if (!(d <= sphere->r + 0.5))
      return "the point (" + num(x) + ", " + num(y) + ") is " + num(std::round(d * 10) / 10) +
             " pixels from the centre of its sphere's circle (" + num(sphere->cx) + "," +
             num(sphere->cy) + "," + num(sphere->r) + "): a highlight lies on the sphere, "
             "within its radius";
  }
  return "";
}

std::string frameRegionProblem(double x, double y, double w, double h, int width, int height) {
  constexpr double kLargest = 2147483647.0;
  for (const double v : {x, y, w, h})
    if (!std::isfinite(v) || v != std::floor(v) || std::abs(v) > kLargest)
      return "X, Y, W and H must be whole numbers of pixels";
  if (x < 0 || y < 0)
    return "the corner (" + num(x) + ", " + num(y) + ") has a negative coordinate; pixel "
           "coordinates start at 0 at the top-left pixel";
  if (w <= 0 || h <= 0) return "the width W and height H must be above 0";
  if (width > 0 && height > 0 && (x + w > width || y + h > height))
    return "the region reaches outside the " + frameText(width, height) + ": X+W must be at most " +
           std::to_string(width) + " and Y+H at most " + std::to_string(height);
  return "";
}

}  // namespace surrogate::stages
