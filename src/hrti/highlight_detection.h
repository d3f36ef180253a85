// The highlight on a sphere in one image (docs/hrti-math.md, "The highlight on a sphere"), and how
// far it can be trusted.
//
// Inside the sphere's circle (less a rim of `rimPixels`, where the outline blurs into the
// background): threshold at `threshold` times the brightest pixel, label
// 8-connected components, take each component's centroid weighted by pixel value (sub-pixel),
// and choose the component nearest the sphere's centre (inter-reflections lie farther out).
//
// A highlight on a glossy black sphere is a small, compact peak far above the sphere's dark
// body. Five measures say whether the chosen one is. They read the disc M within 0.85 of the
// radius (a light in front of the object puts its highlight within sin 45 deg = 0.71 of it;
// the rim beyond reflects the surroundings). P is the brightest value of the sphere, B the
// median of M (the sphere's body), K the chosen component:
//
//     contrast   C = (P - B) / P                 0 on a flat or fully saturated disc
//     spread     S = |{v in M : v >= (B+P)/2}| / |M|
//                                                share of the sphere at least halfway up to
//                                                the peak: about 0.01 for a highlight
//     share      H = |K in M| / |all components in M|
//                                                1 for one spot; low when the brightest pixels
//                                                are scattered over the sphere (texture, noise)
//     fill       F = |K| / (4 pi sqrt(det Sigma)) Sigma the covariance of K's pixel positions
//                                                (each pixel a unit square): 1 for a filled
//                                                ellipse, low for a ring or a crescent
//     elongation E = sqrt(l2 / l1)               l1 >= l2 the eigenvalues of Sigma plus 0.5 px^2
//                                                of blur: 1 round, 0.7 a highlight seen at 45
//                                                degrees, low for a streak
//
// Each measure gives a score that is 1 where highlights lie (on every generated capture of the
// tests, benchmarks and demo: C >= 0.87, S <= 0.014, H = 1, F >= 0.92, E >= 0.77) and falls
// linearly to 0 at a limit; the confidence is the lowest score, at most 0.5 with a second
// candidate (flag Multiple). A measure past its limit refuses the highlight (confidence 0):
// the light direction it would give is not to be trusted.
//
//              score 1 at    limit (refused)      flag
//   contrast   C >= 0.50     C <  0.30            flat
//   spread     S <= 0.03     S >  0.10            large, or saturated when P >= 0.98 and more
//                                                 than 0.10 of M is at 0.98 or above
//   share      H >= 0.70     H <  0.40            not-compact
//   fill       F >= 0.70     F <  0.45            not-compact
//   elongation E >= 0.40     E <  0.20            not-compact
//
// Flags: None when nothing stands out (peak below 5 % of full scale: the light was behind
// the sphere or the flash failed); Multiple when another component is nearly as bright (>= 90 %
// of the chosen peak, >= 3 pixels): the choice is then worth checking on the overview image.
//
//   const Highlight h = detectHighlight(rows, 0, y0, sphere, HighlightOptions());
//   if (!isUsable(h.flag)) refuse(image, h.reason);   // else h.x, h.y with h.confidence 0..1
#pragma once

#include <string>
#include <utility>
#include <vector>

#include "core/image.h"
#include "core/stack.h"
#include "hrti/sphere_detection.h"

namespace surrogate::hrti {

struct HighlightOptions {
  double threshold = 0.8;  // fraction of the brightest pixel inside the sphere
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
  NotCompact,  // refused: the peak is a streak, a ring or scattered pixels
};

// "ok", "multiple", "manual", "none", "flat", "saturated", "large", "not-compact": the carrier's
// highlight/@flag.
const char* flagName(HighlightFlag flag);
// Ok, Multiple and Manual give a light direction; the others do not.
bool isUsable(HighlightFlag flag);

// The measures above, for the record and for choosing the limits (bench, tests).
struct HighlightMeasures {
  double contrast = 0, spread = 0, saturated = 0, fill = 0, elongation = 0;
  double share = 0;  // of the pixels above the threshold, the part in the chosen component
  int area = 0;      // pixels of the chosen component
};

// The limits of the table above.
struct HighlightLimits {
  static constexpr double kGoodContrast = 0.50, kMinContrast = 0.30;
  static constexpr double kGoodSpread = 0.03, kMaxSpread = 0.10;
  static constexpr double kGoodShare = 0.70, kMinShare = 0.40;
  static constexpr double kSaturatedLevel = 0.98;
  static constexpr double kGoodFill = 0.70, kMinFill = 0.45;
  static constexpr double kGoodElongation = 0.40, kMinElongation = 0.20;
  static constexpr double kMultipleCap = 0.5;  // confidence with a second candidate
  static constexpr double kBlurPx2 = 0.5;      // added to Sigma's eigenvalues for elongation
};

struct Highlight {
  double x = 0, y = 0;  // full-image pixels
  HighlightFlag flag = HighlightFlag::None;
  int components = 0;
  double peak = 0;        // brightest value inside the sphere, 0..1
  double confidence = 0;  // 0..1: the lowest score (see above); 1 when given by hand
  HighlightMeasures measures;
  // Why a highlight is refused or doubtful, for people: "18 % of the sphere is at least
  // halfway up to its brightest value (a highlight covers under 10 %)". Empty when Ok.
  std::string reason;
};

// Judges a measured highlight: sets flag (unless None), confidence and reason from
// `measures`, `peak` and whether another candidate is nearly as bright.
void judgeHighlight(Highlight& h, bool secondCandidate);

// `crop` holds rows/columns of one luminance image starting at (cropX0, cropY0).
Highlight detectHighlight(const Image& crop, int cropX0, int cropY0, const DetectedSphere& sphere,
                          const HighlightOptions& options);

// Every image's highlight on every sphere: [image][sphere]. Reads only the square around each
// sphere (ImageStack::readWindow); parallel over images, identical at any thread count.
std::vector<std::vector<Highlight>> detectHighlights(const ImageStack& luminance,
                                                     const std::vector<DetectedSphere>& spheres,
                                                     const HighlightOptions& options, int threads);

}  // namespace surrogate::hrti
