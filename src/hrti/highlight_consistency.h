// The highlights of a stack judged against each other (docs/hrti-math.md, "Checks on the
// lights"): a highlight is the spot that rises with THIS image's light, so a spot that rises in
// most other images too and is bright in most of them is not one, and a frame whose best spot
// gives far less light than the others' highlights has lost its highlight.
//
// For each sphere, each image i whose highlight was detected (flag ok or multiple) at p_i, and
// a disc of radius rho = max(3, 2 sigma) px around p_i (sigma the search's blur, r / 150
// clamped to 0.8..4 px), with D_j = max(0, image_j - median) the rise of image j there:
//
//   rise_j(p_i)   mean of D_j over the disc
//   shared        the images j != i whose highlight is farther than max(3 rho, r / 20) from p_i
//                 (or that have none) and that rise there by at least kSharedRise of rise_i(p_i)
//   steady        mean of the stack's median over the disc / mean of image i over it
//
//   fixed   more than half the other images share the rise AND steady >= kSteadyRatio: a
//           reflection of the room lit by the flash, or dust on the sphere, at the same place in
//           every image, not where this image's light is mirrored (flag fixed, refused). On the
//           real light probes (tests/data/real-rti/lightprobe-*) a highlight has at most 5 of 11
//           images sharing at 10 % and steady at most 0.11; the room's reflections refused as
//           fixed in a frame without its highlight have 6-8 of 11 and 0.17-0.30. Both are
//           required: a highlight on a bright reflection is steady, and neighbouring lights and
//           glare streaks through a highlight are shared
//   flux          image i's rise above the images' per-pixel lower quartile Q, as a share of
//                 the rise full scale leaves room for, (v - Q) / max(0.05, 1 - Q), summed over
//                 the disc of 4 rho around p_i, against the median of the other highlights'
//                 (those not fixed): the quartile, not the median, as where the lights are close
//                 together the highlights overlap and raise the median; the share, as a clipped
//                 highlight on a bright reflection cannot rise far above it
//   faint   flux < kFaintRatio, and the image itself is not dark (its mean in linear light at
//           least kDarkImage of the median image's: a dark frame is exposure-outlier's): the same
//           lamp mirrored in the same sphere gives about the same flux in every image, so the
//           highlight is missing and what was found is a reflection or a remnant of glare (flag
//           faint, refused). On the real light probes and generated captures a highlight gives
//           0.88-1.09 of the median flux; the spots a frame whose highlight was painted out
//           offers give under 0.7 (0.5-0.7 for the glare left beside a small painted disc). A
//           hand-held flash whose distance varies by more than 1.2 times (flux as 1/d^2 where
//           not clipped) would give less: keep its distance, as H-RTI practice does. A near
//           light's distance to each sphere varies with its direction even so: with the
//           distance stated (lightDistancePx below) the flux is corrected for it
//
// Manual highlights are never judged. Fewer than kMinImages images with a detected highlight on
// a sphere: nothing is judged there (too few to tell what is shared).
//
// Each judged highlight also gets its clipped area (Highlight::clippedArea: pixels at full scale
// within kClippedRadius of the radius around it), which exposure-outlier compares.
//
//   judgeAcrossImages(luminance, median, spheres, highlights, linearMeans, threads);  // may refuse some
#pragma once

#include <vector>

#include "core/stack.h"
#include "hrti/highlight_detection.h"
#include "hrti/sphere_detection.h"

namespace surrogate::hrti {

class StackMedian;

struct ConsistencyLimits {
  static constexpr double kSharedRise = 0.10;
  static constexpr double kSteadyRatio = 0.15;
  static constexpr double kFaintRatio = 0.7;
  static constexpr double kDarkImage = 0.3;
  static constexpr int kMinImages = 4;
  static constexpr double kClippedRadius = 0.2;  // of the sphere's radius: Highlight::clippedArea
};

// What was measured for one highlight (for the record and for choosing the limits).
struct HighlightSupport {
  bool judged = false;
  double rise = 0;    // rise_i(p_i), 0..1
  double steady = 0;  // median / image over the disc
  double flux = 0;    // the rise summed over 4 rho, against the median of the others'
  int shared = 0;     // images sharing the rise
};

// Judges every detected highlight of `highlights` ([image][sphere], as detectHighlights gives
// them) against the others, and refuses the fixed and faint ones (flag, confidence 0, reason).
// `imageMeans`: each image's mean in linear light (empty: faint is not judged). Returns what was
// measured, [image][sphere]. Reads small windows of the stack; identical at any thread count.
// lightDistancePx > 0: the lights' stated distance from the frame's centre (docs/hrti-math.md,
// "Near lights"), in pixels: a highlight whose light was farther from the sphere than the
// median is brought to the median distance, its flux times (t / t_median)^2 with t the distance
// from its mirror point to the light placed at that distance along its reflected ray
// (positionAtDistance), as a near flash on the far side of the frame gives the sphere 1/t^2 of
// its light; never lowered (a clipped highlight's flux grows far less than 1/t^2).
std::vector<std::vector<HighlightSupport>> judgeAcrossImages(const ImageStack& luminance, const StackMedian& median,
                                                             const std::vector<DetectedSphere>& spheres,
                                                             std::vector<std::vector<Highlight>>& highlights,
                                                             const std::vector<double>& imageMeans, int threads,
                                                             double lightDistancePx = 0);

}  // namespace surrogate::hrti
