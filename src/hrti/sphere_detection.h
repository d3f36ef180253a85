// The reflective spheres in the median of the stack (docs/hrti-math.md, "Spheres in the median
// image"; the median: hrti/stack_median.h).
//
//   1. 7x7 median filter: flattens texture, keeps the sphere's outline sharp
//   2. Sobel gradient, magnitude and direction
//   3. circle Hough transform accumulated from the gradient magnitude itself (no binarisation):
//      each edge pixel p with gradient direction g votes, for every candidate radius r, along
//      an arc of +-pi/12 around the point
//            c = p - r (cos(g + phi), sin(g + phi)),   |phi| <= pi/12
//      i.e. into the dark sphere. Radii are independent and run in parallel; the best
//      (x, y, r), score normalised by what a perfect circle of that radius reaches, wins.
//   4. sub-pixel refinement: along 360 rays from the centre, the sub-pixel maximum of the
//      radial gradient (parabola through 3 samples) gives an edge point; a least-squares
//      circle fit (algebraic, then geometric Gauss-Newton) with outlier rejection gives
//      (cx, cy, r).
// Steps 1-3 run on the median reduced by an integer factor to about `coarseWidth` pixels
// (StackMedian::coarse(); the Hough transform is the expensive part), step 4 and the
// highlight check below at full resolution around each candidate (StackMedian::window()).
// Radii run from minRadius to half the frame's smaller side (a sphere filling nine tenths of
// the frame's height), every coarse pixel.
//
// A circle is not yet a sphere: the reflected scene, a round object, a dark patch of
// background all give circles. What only a sphere gives is a highlight that moves with the
// light. Each candidate (the 40 strongest distinct circles and the four strongest of each
// octave of radius) is kept only if
//   - confidence >= minConfidence: the fraction of 360 rays from the centre whose strongest
//     outward edge is strong (above a quarter of the median edge strength) and lies on the
//     fitted circle (within a pixel, or 1 % of the radius when more): a whole, clean rim scores
//     near 1, texture around a circle does not;
//   - evidence >= 0.5: the share of the images in which detectHighlight (against the stack's
//     median, hrti/highlight_detection.h) finds a usable highlight within 0.75 of the radius,
//     provided those highlights do not all sit within 5 % of the radius of each other (a
//     spot that stays put is a reflection or a speck). With fewer than three images there is
//     nothing to compare with: the circle must then be much darker inside (0.8 r) than
//     around it (1.15 to 1.4 r), as a black sphere is.
// Kept circles are taken by confidence x evidence, skipping any that overlaps one taken: a
// reflection in a sphere shows the moving highlight in few images, a circle around a sphere
// has a weaker rim than the sphere's.
// Without a kept circle, Error(Input) names the strongest circles tried and why each failed.
//
//   SphereDetectionOptions o;                     // whole frame, up to 4 spheres
//   o.regions.push_back({900, 0, 300, 250});      // or: one sphere in this region
//   StackMedian median(luminance, o.coarseWidth, o.threads);
//   std::vector<DetectedSphere> s = detectSpheres(median, o);
#pragma once

#include <string>
#include <utility>
#include <vector>

#include "core/image.h"

namespace surrogate::hrti {

struct Rect {
  int x = 0, y = 0, w = 0, h = 0;
};

class StackMedian;

struct DetectedSphere {
  double cx = 0, cy = 0, r = 0;  // pixels; origin at the centre of the top-left pixel, y down
  double confidence = 0;  // share of the rim that is a clean edge on the fitted circle
  double evidence = 0;    // share of the images with a moving highlight in front (1 by hand)
  bool byHand = false;    // given by hand (--sphere): confidence and evidence measure nothing
  // Standard errors (1 sigma, pixels) of the rim fit's centre (each axis) and radius, from its
  // residuals (the fit's covariance, at most 12 independent arcs of rim counted: rimSigmas in
  // hrti/rim_fit.cpp); uncalibrated, and blind to a bias of where the silhouette lies on
  // its edge (1-3 px on PSBox's light probes, docs/hrti-math.md "What limits the accuracy").
  // 0 when not measured (a circle given by hand inside the frame: not refined).
  double centreSigmaPx = 0, radiusSigmaPx = 0;
};

struct SphereDetectionOptions {
  double minRadius = 10;        // pixels (and 6 pixels of the reduced median): a sphere 3 % of a 800 px frame
  double maxRadius = 0;         // pixels; 0 = a quarter of the image's smaller side
  std::vector<Rect> regions;    // user regions, one sphere each; empty = search the frame
  int maxSpheres = 4;           // when searching the whole frame
  double minConfidence = 0.5;   // weaker candidates are not spheres
  int coarseWidth = 800;        // about the width of the reduced median the Hough transform runs on
  int threads = 0;              // not recorded: results are identical at any count

  std::vector<std::pair<std::string, std::string>> toParameters() const;
  static SphereDetectionOptions fromParameters(const std::vector<std::pair<std::string, std::string>>& p);
};

// Throws Error(Input) when no sphere is found, suggesting --sphere-roi or --sphere. The median
// must have been reduced for options.coarseWidth.
std::vector<DetectedSphere> detectSpheres(const StackMedian& median, const SphereDetectionOptions& options);
// The same, the circles searched and their rims fitted in `rim`, an upper quantile of the same
// stack (kRimQuantile): the backdrop as lit in most photographs and the cast shadows, which move,
// left out. In the lower median a backdrop lit in half the photographs can come out dark
// around a black sphere (one darkened frame of LightProbe-1 hid its rim from every circle), and
// a sphere's own shadows can outline a larger circle (a generated capture's sphere of radius 45
// was taken as one of 59). The highlights are still judged against the median.
inline constexpr double kRimQuantile = 0.75;
std::vector<DetectedSphere> detectSpheres(const StackMedian& median, const StackMedian& rim,
                                          const SphereDetectionOptions& options);
// A circle given by hand that the frame's edge cuts, fitted to its visible rim in `rim` (the
// stack's kRimQuantile, or its median with fewer than four images): the rim searched within
// kGivenRimMargin pixels (kGivenRimMarginShare of the radius when more) of the given circle,
// along the rays whose rim lies inside the frame only. The result is byHand; its confidence is
// the share of those rays whose edge lies on the fitted circle, with its standard errors. The
// caller decides whether to use it: a fit far from the given circle, or on a rim that is not a
// clean edge, did not find the sphere.
inline constexpr double kGivenRimMargin = 4, kGivenRimMarginShare = 0.03;
DetectedSphere fitVisibleRim(const StackMedian& rim, const DetectedSphere& given);
// The same on one image taken as the median (tests on drawn images).
std::vector<DetectedSphere> detectSpheres(const Image& median, const SphereDetectionOptions& options);

}  // namespace surrogate::hrti
