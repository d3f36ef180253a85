// Plausibility checks on a capture's light directions (docs/hrti-math.md, "Checks on the
// lights"): what a real capture's lights cannot look like, so that a phantom sphere, a
// misplaced circle or a misfired flash stops the run instead of becoming a result.
//
//   lights-below-horizon  a light behind the object's plane by more than its uncertainty (its
//                         95 % bound, LightCheckInput::uncertaintyDeg, at most 5 degrees; 2
//                         degrees when not measured): its highlight lies beyond 0.71 of the
//                         sphere's radius, where the light is behind the object and could not
//                         have lit it, and even the bound does not bring it in front
//   spheres-overlap       two spheres whose circles overlap or nest: one is a reflection in the
//                         other, or the same sphere twice
//   spheres-disagree      with two or more spheres, the median angle between the directions
//                         they give for the same image is above 15 degrees
//   lights-clustered      the median angle between two lights is below 3 degrees: the light was
//                         not moved, or the "highlights" are not of the light
//   exposure-outlier      an image whose highlight peaks under half the median peak of the
//                         images, whose highlight's clipped area (full scale within 0.2 of the
//                         radius) is over twice the median image's, or whose mean brightness
//                         is under 0.1 or over 10 times the median of the three images lit
//                         from the nearest directions: a misfired flash, a dark or
//                         overexposed frame (too dark or too bright, named as such)
//
// Each check that fails names the images it concerns; the stage that runs them stops the run
// unless the user accepts the check by name (a recorded decision).
//
//   LightCheckInput in{lights, spheres, perSphere, means, names};
//   for (const LightCheck& c : checkLights(in)) if (c.failed) ...
#pragma once

#include <array>
#include <optional>
#include <string>
#include <vector>

#include "hrti/sphere_detection.h"

namespace surrogate::hrti {

inline constexpr const char* kCheckBelowHorizon = "lights-below-horizon";
inline constexpr const char* kCheckSpheresOverlap = "spheres-overlap";
inline constexpr const char* kCheckSpheresDisagree = "spheres-disagree";
inline constexpr const char* kCheckLightsClustered = "lights-clustered";
inline constexpr const char* kCheckExposureOutlier = "exposure-outlier";
// Checked after each fit (RtiFit), not with the lights: see residualOutliers below.
inline constexpr const char* kCheckResidualOutlier = "residual-outlier";
// Checked by highlight detection, before the highlights are judged: see frameMovedCheck below.
inline constexpr const char* kCheckFrameMoved = "frame-moved";
// Every check's name: frame-moved, those of checkLights in the order they run, then
// residual-outlier.
const std::vector<std::string>& lightCheckNames();

struct LightCheckLimits {
  static constexpr double kHorizonMarginDeg = 2;     // without a measured uncertainty
  static constexpr double kMaxHorizonMarginDeg = 5;  // with one: its 95 % bound, at most this
  static constexpr double kMaxDisagreementDeg = 15;
  static constexpr double kMinSpreadDeg = 3;
  // exposure-outlier, in linear light (LightCheckInput): a frame's mean against its three
  // nearest-lit neighbours' (the real light probes' frames range from 0.25 to 2.5 of theirs,
  // raking lights darkening a frame legitimately), its highlight's peak against the median peak.
  static constexpr double kDarkRatio = 0.1, kBrightRatio = 10;
  static constexpr double kPeakRatio = 0.5;
  // ... and the clipped area around its highlight against the median of the images' (at least
  // kMinClippedPx): the real light probes' frames range 0.51-1.42 of it, a frame at 300 %
  // exposure 2.7-4.5.
  static constexpr double kClippedRatio = 2.0, kMinClippedPx = 16;
  static constexpr int kNeighbours = 3;
  // residual-outlier: an image the fitted model misses by more than three times the median
  // image's RMSE and by more than eight robust deviations (1.4826 MAD) above it.
  static constexpr double kResidualRatio = 3, kResidualDeviations = 8;
};

struct LightCheckInput {
  std::vector<std::array<double, 3>> lights;  // one unit direction per image
  std::vector<DetectedSphere> spheres;
  // [image][sphere]: the direction that sphere gives for that image, when its highlight is usable
  std::vector<std::vector<std::optional<std::array<double, 3>>>> perSphere;
  // Exposures, in linear light (an sRGB value decoded): what exposure-outlier compares.
  std::vector<double> imageMeans;  // per image, 0..1; empty: not compared
  std::vector<double> highlightPeaks;  // per image, 0..1, the brightest usable highlight; 0 none
  // Per image, the pixels at full scale around its highlight (Highlight::clippedArea, the
  // largest over the spheres; 0 none): a frame exposed too long clips a wider halo.
  std::vector<double> clippedAreas;
  std::vector<std::string> names;  // per image, as the user names it (the shot)
  // Per image, the 95 % bound in degrees on its light's angle from the true direction
  // (hrti/light_uncertainty.h); empty when not measured (lights given by a file).
  std::vector<double> uncertaintyDeg;
};

struct LightCheck {
  std::string name;
  bool failed = false;
  std::string detail;        // in plain words, with the figures
  std::vector<int> images;   // the images it names (indices into the input)
};

std::vector<LightCheck> checkLights(const LightCheckInput& input);

// residual-outlier: the images (indices) whose fit RMSE stands out of the others' (limits
// above). A photograph the model cannot explain (a misfired flash, a moved object, a wrong light)
// pulls every pixel's coefficients towards itself. Fewer than five images: none.
std::vector<int> residualOutliers(const std::vector<double>& perImageRmse);
// The check residual-outlier on a fit's per-image RMSE, its images named by `names`.
LightCheck residualCheck(const std::vector<double>& perImageRmse, const std::vector<std::string>& names);

// frame-moved: the images (movedPx: how far each moved against the stack, full-resolution
// pixels, hrti/frame_registration.h; negative when not measured) that moved more than limitPx.
// A frame whose camera, sphere or object moved gives every pixel of the fit a sample of another
// point, and its light is measured on a circle that is not where its sphere is.
LightCheck frameMovedCheck(const std::vector<double>& movedPx, double limitPx, const std::vector<std::string>& names);

// The angle between two directions, in degrees.
double angleDeg(const std::array<double, 3>& a, const std::array<double, 3>& b);

}  // namespace surrogate::hrti
