// The geometry of a ColorChecker's patch grid (private to src/colour): the homography from the
// grid's unit square to the image, where each patch lies in it, and the refinement of a rough
// place (OpenCV's mcc is often 10 px off) against the edges between patches and the black gaps.
//
//   Grid g{corners, 0.2};
//   Homography h = homography(g.corners);
//   Point p = h.map(0.5, 0.5);                 // the grid's centre in the image
//   g = refineGrid(grey, g, {4.0, 1.5, 0.8});  // edges aligned to ~1 px
//
// Unit square: u from the edge of patch 0 to that of patch 5 (0..1), v from patch 0 to patch
// 18. Column c spans u in [c, c + 1 - gap] / (6 - gap): `gap` is the black gap between patches
// as a fraction of the pitch (about 0.2 on an X-Rite chart; measured by the refinement).
#pragma once

#include <array>
#include <vector>

#include <opencv2/core.hpp>

#include "colour/chart_detection.h"

namespace surrogate::colour {

struct Homography {
  double m[3][3] = {{1, 0, 0}, {0, 1, 0}, {0, 0, 1}};
  Point map(double u, double v) const;
  Homography inverse() const;
};
// The homography taking (0,0), (1,0), (1,1), (0,1) to the four corners (Heckbert's closed form).
Homography homography(const std::array<Point, 4>& corners);

struct Grid {
  std::array<Point, 4> corners;
  double gap = 0.2;
};
inline constexpr double kDefaultGap = 0.2;
// The measured part of a patch: its centre +- this fraction of the pitch (half the pitch each
// way, so corners a few pixels off still measure the patch alone).
inline constexpr double kCentralHalf = 0.25;
// Above this colour misfit of the best rotation, mcc's box is not a ColorChecker (a phantom).
inline constexpr double kMaxOrientationMisfit = 0.25;

struct UnitRect {
  double u0, u1, v0, v1;
};
// Patch k's own area in the unit square.
UnitRect patchRect(int k, double gap);
// Its measured part: the patch's centre +- `half` of the pitch.
UnitRect centralRect(int k, double gap, double half);

// The mean side of a patch in pixels, and the gap that gives it back (patchRegions uses it).
double patchSideOf(const Grid& grid);
double gapFromPatchSide(const std::array<Point, 4>& corners, double patchSide);

// The grid moved so that every patch's edges sit on falls of brightness towards the gaps in
// `grey` (CV_32F), at each Gaussian scale in turn (pixels, coarse to fine): a pattern search over
// the corners, the whole grid's shift, scale and turn, and the gap. Serial and deterministic.
Grid refineGrid(const cv::Mat& grey, Grid grid, const std::vector<double>& sigmas);

}  // namespace surrogate::colour
