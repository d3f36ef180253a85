// The highlight on a sphere in one image (docs/hrti-math.md, "The highlight on a sphere"), and how
// far it can be trusted.
//
// Real highlights are not tidy spots: a saturated core with a glare streak through it, dust
// specks and the reflected scene around it, a window or a lamp reflected in every frame. What
// tells the highlight apart is that it MOVES with the light. So the search reads the image's
// excess over the stack's per-pixel median (hrti/stack_median.h), which removes everything
// that is there in every frame (reflections, dust, the sphere's own body):
//
//   1. D = max(0, image - median) inside the disc within 0.9 of the radius (and `rimPixels`
//      from the edge; a light in front of the object puts its highlight within sin 45 deg =
//      0.71 of it, the rim beyond reflects the surroundings at grazing angles);
//   2. B = D blurred by a Gaussian of sigma = r / 150 (0.8 to 4 px): a highlight's core is a
//      blob several pixels wide and keeps its height, a hot pixel or a thin glare streak
//      does not;
//   3. the peak of B; the 8-connected pixels around it with B >= threshold * peak; the
//      centroid of that core weighted by B - threshold * peak (sub-pixel), not of the streak or
//      halo around it;
//   4. where the image is clipped inside the core in a plateau at least 6 px deep, the
//      plateau's deepest point instead (the centre of the largest disc inside it): a glare
//      streak clipped with the highlight is thinner, so it pulls a centroid but not that point.
// Without a median (a stack of fewer than three images) D is the image itself.
//
// Seven measures say whether the peak is a highlight. M is the disc within 0.85 of the
// radius, P the image's brightest value at the core, Bd the median of the image over M:
//
//     contrast     C = (P - Bd) / P               0 on a flat or fully saturated disc
//     spread       S = |{B >= peak/2} in M| / |M| share of the sphere at least halfway up
//                                                 to the peak: about 0.01 for a highlight
//     saturated      |{image >= 0.98} in M| / |M|
//     compactness  K = peak of B / max of D within 2 sigma of it
//                                                 ~1 for a blob several pixels wide, 1/(2 pi
//                                                 sigma^2) for a single hot pixel
//     elongation   E = sqrt(l2 / l1)              l1 >= l2 the eigenvalues of the core's
//                                                 covariance plus 0.5 px^2: low for a streak
//     fill         F = |core| / (4 pi sqrt(det Sigma))  Sigma that covariance: 1 for a filled
//                                                 ellipse, low for a ring or a crescent
//     body rise    R = upper quartile of D over M / peak of B: a mirror sphere's body does
//                                                 not follow the light, a matte object's does
//
//              score 1 at    limit (refused)      flag
//   contrast   C >= 0.80     C <  0.55            flat
//   spread     S <= 0.03     S >  0.10            large, or saturated when P >= 0.98 and more
//                                                 than 0.10 of M is at 0.98 or above
//   compact    K >= 0.85     K <  0.60            not-compact (a speck, a hot pixel, a broad glow)
//   elongation E >= 0.30     E <  0.15            not-compact (a streak)
//   fill       F >= 0.70     F <  0.45            not-compact (a ring)
//   body rise  R <= 0.15     R >  0.30            shaded (a matte round object)
//
// The confidence is the lowest score, at most 0.5 with a second candidate (another core at
// least 90 % of the peak; flag Multiple, the brighter one is used). None when the peak of B is
// below 5 % of full scale: nothing in this image is brighter than in the others there (the
// light was behind the sphere, or the flash did not fire).
//
//   const Highlight h = detectHighlight(image, &medianCrop, x0, y0, sphere, HighlightOptions());
//   if (!isUsable(h.flag)) refuse(image, h.reason);   // else h.x, h.y with h.confidence 0..1
#pragma once

#include <string>
#include <utility>
#include <vector>

#include "core/image.h"
#include "core/stack.h"
#include "hrti/sphere_detection.h"

namespace surrogate::hrti {

class StackMedian;

struct HighlightOptions {
  double threshold = 0.8;  // fraction of the peak (of B, above) that bounds the highlight's core
  int rimPixels = 2;       // excluded at the sphere's edge

  std::vector<std::pair<std::string, std::string>> toParameters() const;
  static HighlightOptions fromParameters(const std::vector<std::pair<std::string, std::string>>& p);
};

enum class HighlightFlag {
  Ok,          // one compact peak
  Multiple,    // used, but another candidate is nearly as bright
  Manual,      // given by hand
  None,        // no highlight: nothing stands out of the sphere's body
  Flat,        // refused: the sphere's disc has no peak (a flat or featureless frame)
  Saturated,   // refused: a large part of the disc is saturated (an overexposed frame)
  Large,       // refused: bright over a large part of the disc, not a highlight
  NotCompact,  // refused: the peak is a single pixel, a speck or a streak
  Shaded,      // refused: the whole disc follows the light (a matte object, not a mirror sphere)
  // Judged against the other images (hrti/highlight_consistency.h):
  Fixed,       // refused: the spot rises in other images too, or is bright in most: a reflection or dust
  Faint,       // refused: far less light than the other images' highlights: the highlight is missing
};

// "ok", "multiple", "manual", "none", "flat", "saturated", "large", "not-compact", "shaded", "fixed",
// "faint": the carrier's highlight/@flag.
const char* flagName(HighlightFlag flag);
// Ok, Multiple and Manual give a light direction; the others do not.
bool isUsable(HighlightFlag flag);

// The measures above, for the record and for choosing the limits (bench, tests).
struct HighlightMeasures {
  double contrast = 0, spread = 0, saturated = 0, compactness = 0, elongation = 0, bodyRise = 0, fill = 0;
  int area = 0;  // pixels of the core
};

// The limits of the table above.
struct HighlightLimits {
  static constexpr double kGoodContrast = 0.80, kMinContrast = 0.55;
  static constexpr double kGoodSpread = 0.03, kMaxSpread = 0.10;
  static constexpr double kSaturatedLevel = 0.98;
  static constexpr double kGoodCompactness = 0.85, kMinCompactness = 0.60;
  static constexpr double kGoodBodyRise = 0.15, kMaxBodyRise = 0.30;
  static constexpr double kGoodFill = 0.70, kMinFill = 0.45;
  static constexpr double kGoodElongation = 0.30, kMinElongation = 0.15;
  static constexpr double kMultipleCap = 0.5;  // confidence with a second candidate
  static constexpr double kSecondPeak = 0.9;   // a second core this high (of the peak) is a candidate
  static constexpr double kBlurPx2 = 0.5;      // added to Sigma's eigenvalues for elongation
};

struct Highlight {
  double x = 0, y = 0;  // full-image pixels
  HighlightFlag flag = HighlightFlag::None;
  int components = 0;
  double peak = 0;        // the brightest value at the highlight, 0..1 (flag none: the highest rise over the median)
  double confidence = 0;  // 0..1: the lowest score (see above); 1 when given by hand
  HighlightMeasures measures;
  // The covariance (pixels^2) of (x, y) as an estimate of the point where the light's mirror
  // reflection is, 1 sigma, uncalibrated; 0 when not measured (by hand). A core's centroid: the
  // covariance of its pixel positions divided by the blur footprints (4 pi sigma^2 pixels)
  // among its unsaturated pixels, at least 1. A plateau's deepest point: the covariance of the
  // plateau's points within 80 % of its greatest depth (long along a plateau with no one centre).
  double covXX = 0, covXY = 0, covYY = 0;
  // Pixels at full scale (kSaturatedLevel) within 0.2 of the radius around it, counted by
  // judgeAcrossImages (hrti/highlight_consistency.h): what exposure-outlier compares for a frame
  // too bright. 0 when not counted.
  double clippedArea = 0;
  // Why a highlight is refused or doubtful, for people: "18 % of the sphere is at least
  // halfway up to its brightest value (a highlight covers under 10 %)". Empty when Ok.
  std::string reason;
};

// Judges a measured highlight: sets flag (unless None), confidence and reason from
// `measures`, `peak` and whether another candidate is nearly as bright.
void judgeHighlight(Highlight& h, bool secondCandidate);

// `crop` holds rows/columns of one luminance image starting at (cropX0, cropY0); `median`, when
// given, the stack's median over the same rectangle (same size).
Highlight detectHighlight(const Image& crop, const Image* median, int cropX0, int cropY0,
                          const DetectedSphere& sphere, const HighlightOptions& options);
// The same without a median: D is the image itself (drawn test images, one-image stacks).
Highlight detectHighlight(const Image& crop, int cropX0, int cropY0, const DetectedSphere& sphere,
                          const HighlightOptions& options);

// The rectangle detectHighlight reads around a sphere (its square and two pixels around it,
// clipped to the frame): x0, y0, x1, y1 with x1, y1 exclusive; empty when off the frame.
Rect highlightWindow(const DetectedSphere& sphere, int width, int height);

// Every image's highlight on every sphere: [image][sphere]. Reads only the square around each
// sphere (ImageStack::readWindow) and, with `median` and at least three images, the median
// there; parallel over images, identical at any thread count.
std::vector<std::vector<Highlight>> detectHighlights(const ImageStack& luminance,
                                                     const std::vector<DetectedSphere>& spheres,
                                                     const HighlightOptions& options, int threads,
                                                     const StackMedian* median = nullptr);

}  // namespace surrogate::hrti
