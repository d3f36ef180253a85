// The sphere's rim at full resolution (docs/hrti-math.md, "Spheres in the median image", step 4):
// the circle a coarse search or a hand gave, refined on the stack's median. Along 360 rays from
// the centre, the sub-pixel maximum of the radial gradient (parabola through 3 samples) within
// `margin` of the circle gives an edge point; faint edges (under a quarter of the median
// strength) are left out; a least-squares circle (hrti/circle_fit.h) through the rest, three
// passes with the margin shrinking to 3 px. A ray whose rim point lies outside the frame is no
// evidence of an edge and is not searched (a sphere cut by the frame's edge).
//
//   DetectedSphere s = refineRim(median, cx, cy, r, margin);   // s.confidence, s.centreSigmaPx
#pragma once

#include <opencv2/core.hpp>

#include <vector>

#include "core/image.h"
#include "hrti/sphere_detection.h"

namespace surrogate::hrti {

class StackMedian;

// A 16-bit image as floats in 0..1.
cv::Mat medianToFloat(const Image& im);

// Values the full-resolution median gives over rows [y0, y1) and columns [x0, x1) (clipped to
// the frame), as floats in 0..1, and where that window lies (empty when off the frame).
struct MedianWindow {
  cv::Mat values;
  int x0 = 0, y0 = 0;
};
MedianWindow medianWindow(const StackMedian& median, int x0, int y0, int x1, int y1);

// The circle refined on its rim, with its standard errors (DetectedSphere::centreSigmaPx,
// radiusSigmaPx) and confidence: the share of all 360 rays whose edge lies on the circle, or with
// `ofVisible` of the rays inside the frame. Fewer than 20 edge points: the circle as given, with
// confidence 0.
DetectedSphere refineRim(const StackMedian& median, double cx, double cy, double r, double margin,
                         bool ofVisible = false);

// The parts of the full-resolution median that refineRim's first pass over the circle
// (cx, cy, r) searched within `margin` reads: of its window's 64 x 64 tiles (StackMedian::kTile)
// those that reach the ring its profiles sample (with the blur's and the gradients' reach
// around it), in runs along each row of tiles. The inside of a large circle and the corners of its
// window are not read: the circle's refinement depends on no value there. For
// StackMedian::prepare; later passes, on a circle moved by the fit, read what they need.
std::vector<Rect> rimReads(const StackMedian& median, double cx, double cy, double r, double margin);

namespace detail {
// The gradients of the blurred median over a window whose pixel (0, 0) is the frame's (x0, y0),
// `cols` floats a row.
struct RimGradients {
  const float *gx, *gy;
  int cols, rows, x0, y0;
};
// The radial derivative along the ray from (cx, cy) in direction (ca, sa) at the distances
// ts[0..n): both gradients interpolated bilinearly, NaN where the 2 x 2 pixels leave the window.
// refineRim's profiles, in two variants for the test that compares them (the same bits):
// radialProfileAvx2 returns false (and does nothing) where it is not compiled.
void radialProfilePlain(const RimGradients& g, double cx, double cy, double ca, double sa, const double* ts,
                        std::size_t n, double* out);
bool radialProfileAvx2(const RimGradients& g, double cx, double cy, double ca, double sa, const double* ts,
                       std::size_t n, double* out);
// refineRim reading the whole window of each pass, inside the ring too: what the tests compare
// refineRim with (the same bits).
DetectedSphere refineRimWholeWindow(const StackMedian& median, double cx, double cy, double r, double margin,
                                    bool ofVisible = false);
}  // namespace detail

}  // namespace surrogate::hrti
