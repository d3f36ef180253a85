// How far a light direction can be trusted: a 95 % bound, in degrees, on the angle between the
// direction measured from the highlights and the true one (docs/hrti-math.md, "The uncertainty
// of a light").
//
// Each sphere's direction L(hx, hy, cx, cy, r) is a function of the highlight's centre and the
// circle (hrti/light_direction.h, orthographic or perspective). Its inputs' covariance
//   - the highlight's centre: Highlight::covXX/covXY/covYY when the estimator gives them; else
//     from the core's extent (its area, the share of the sphere above half the peak); a
//     highlight placed by hand kHandPx in each axis;
//   - the circle: DetectedSphere::centreSigmaPx (each axis) and radiusSigmaPx when the rim fit
//     gives them; else a share of the radius; a circle given by hand kHandPx;
// is carried to L through its Jacobian (central differences), onto the plane tangent to the
// unit sphere at L: a 2x2 covariance in radians^2. A doubtful highlight (confidence under 1,
// a second candidate, a saturated core) widens its centre's covariance. With several spheres the
// image's light is the normalised sum of theirs (stages/light_directions_stage.cpp): their
// covariances are carried through it, and their spread about it (the sample covariance of the
// mean) is added, so spheres that disagree widen the bound. A floor (kFloorDeg, each axis) stands
// for what no term measures: JPEG blocks, the camera model, the sphere's roundness.
// The bound is kScale times the radius that holds 95 % of that 2D Gaussian. kScale and the
// fallbacks' factors are calibrated on generated captures and the real light probes
// (tests/hrti/test_light_uncertainty.cpp, tests/e2e/test_light_uncertainty_e2e.cpp).
//
//   std::vector<SphereEvidence> e = {{spheres[0], highlights[n][0]}};
//   double deg = lightUncertaintyDeg(e, nullptr);   // orthographic
#pragma once

#include <array>
#include <vector>

#include "hrti/highlight_detection.h"
#include "hrti/light_direction.h"
#include "hrti/sphere_detection.h"

namespace surrogate::hrti {

struct LightUncertaintyModel {
  // A circle or a highlight placed by hand: 1 sigma, pixels, each axis (and the radius).
  static constexpr double kHandPx = 1.5;
  // The highlight's centre, from its covariance Sigma (Highlight::covXX..): a symmetric core's
  // centroid is its centre whatever its size; what moves it off the mirror point is asymmetry
  // (a glare streak, a clipped side, an extended lamp seen obliquely), Sigma's excess over its
  // smaller eigenvalue l2. Covariance taken: kAsymmetry^2 (Sigma - l2 I) + kSpread^2 Sigma +
  // kMinHighlightPx^2 I.
  static constexpr double kAsymmetry = 0.25;
  static constexpr double kSpread = 0.0;
  static constexpr double kMinHighlightPx = 0.05;
  // The circle: the rim fit's standard errors times kCircleFactor (the edge's bias along whole
  // arcs, which the fit's residuals do not show); without them kCircleShare of the radius.
  static constexpr double kCircleFactor = 1.5;
  static constexpr double kCircleShare = 0.003;
  static constexpr double kFloorDeg = 0.45;  // per axis, 1 sigma
  static constexpr double kScale = 1.0;     // bound = kScale * the 95 % radius
};

// One sphere's evidence for one image's light: the circle and the highlight on it (usable).
struct SphereEvidence {
  DetectedSphere sphere;
  Highlight highlight;
};

// A light's covariance on the plane tangent to it (radians^2), and what it is made of.
struct LightCovariance {
  std::array<double, 3> direction{0, 0, 1};
  double c[2][2] = {{0, 0}, {0, 0}};  // in the basis tangentBasis(direction)
  double highlightDeg = 0, circleDeg = 0, spreadDeg = 0;  // each term's 1-sigma size (rms of its axes)
};

// The covariance of the (normalised sum) direction from these spheres' evidence; `camera` null:
// orthographic. Empty evidence: Error(Internal).
LightCovariance lightCovariance(const std::vector<SphereEvidence>& evidence, const CameraIntrinsics* camera);

// The 95 % bound in degrees (model above) of the light these spheres give.
double lightUncertaintyDeg(const std::vector<SphereEvidence>& evidence, const CameraIntrinsics* camera);

// One sphere's direction's covariance on the plane tangent to it (radians^2, basis
// tangentBasis(direction)) from its inputs' covariance `inputs` (pixels^2, order hx, hy, cx, cy,
// r), through the model's Jacobian: the propagation alone, without the model's terms.
LightCovariance propagate(const DetectedSphere& sphere, double hx, double hy, const double inputs[5][5],
                          const CameraIntrinsics* camera);

// Two unit vectors orthogonal to l and to each other: the basis of LightCovariance::c.
void tangentBasis(const std::array<double, 3>& l, std::array<double, 3>& e1, std::array<double, 3>& e2);

// The radius holding `p` of a zero-mean 2D Gaussian of covariance c (any units).
double gaussianRadius(const double c[2][2], double p);

// The covariance (px^2) taken for a highlight's centre: its own when measured, else as above.
void highlightCovariance(const Highlight& h, const DetectedSphere& sphere, double out[2][2]);
// The 1-sigma errors (px) taken for a circle's centre (each axis) and radius.
void circleSigmas(const DetectedSphere& sphere, double& centrePx, double& radiusPx);

}  // namespace surrogate::hrti
