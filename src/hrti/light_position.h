// The 3D position of a light from its highlights on two or more spheres (dissertation 6.2,
// future work there), in two forms: below, a perspective camera of known intrinsics and spheres
// of known size (millimetres, camera frame); further down, the orthographic camera in frame
// coordinates (pixels; issue 53's conventions), with an uncertainty and a verdict, which the
// pipeline uses.
//
// With the camera's intrinsics and the real sphere diameter, each sphere's centre is known
// in millimetres (camera frame, camera at the origin); each highlight is a point P_k on its
// sphere from which the light lies along the reflected direction L_k. The light is the point
// X nearest to all rays in the least-squares sense:
//     sum_k (I - L_k L_k^T) X = sum_k (I - L_k L_k^T) P_k
// residualMm is the RMS distance from X to the rays. When the rays are nearly parallel (a
// distant or grazing light: the system is ill-conditioned) nearParallel is set and X is
// placed 10 m along the mean direction from the mean highlight point.
#pragma once

#include <array>
#include <string>
#include <vector>

#include "hrti/highlight_detection.h"
#include "hrti/light_direction.h"
#include "hrti/light_uncertainty.h"

namespace surrogate::hrti {

struct SphereGeometry {
  DetectedSphere sphere;
  double diameterMm = 0;
};

struct LightPosition {
  double x = 0, y = 0, z = 0;  // mm, camera frame
  double residualMm = 0;
  bool nearParallel = false;
};

LightPosition lightPositionFromSpheres(const std::vector<SphereGeometry>& spheres,
                                       const std::vector<Highlight>& perSphere,
                                       const CameraIntrinsics& camera);

// ---- Near lights in frame coordinates (docs/hrti-math.md, "Light positions from two spheres")
//
// Frame coordinates (pixels of the frame the spheres were found in, W x H): origin at image
// point ((W-1)/2, (H-1)/2) on the object's plane, x right, y up, z towards the camera; the
// camera is orthographic (V = (0, 0, 1)). A sphere of circle (cx, cy, r) rests on the plane:
// its centre is C = (cx - (W-1)/2, (H-1)/2 - cy, r). Its highlight (hx, hy) is the mirror point
//     N = ((hx - cx) / r, -(hy - cy) / r, nz),   P = C + r N,   L = 2 nz N - V
// and the light lies on the ray P + t L, t > 0. With two or more spheres the light is the point
// X nearest to the rays (least squares, as above). Its uncertainty is light_uncertainty.h's:
// each sphere's inputs (hx, hy, cx, cy, r) with the covariances that model takes
// (highlightCovariance, circleSigmas), plus its floor (kFloorDeg, 1 sigma per axis) on each
// ray's direction, carried to X through the Jacobian by central differences: a 3x3 covariance.
// A light's direction is X / |X| and its distance |X| (docs "conventions": D = |X| / W).
//
//   std::vector<SphereEvidence> e = {{spheres[0], h[n][0]}, {spheres[1], h[n][1]}};
//   NearLightPosition p = positionFromSpheres(e, width, height);
//   if (!p.trusted) fallBack(p.reason);   // else p.position, p.distanceBoundPx ...

using Vec3 = std::array<double, 3>;

// When a triangulated position is trusted (docs/hrti-math.md gives the figures behind them).
struct NearLightRule {
  // The 95 % bound on |X| at most this share of |X|: the per-pixel directions' error it leaves
  // at the frame's edge is at most this share of the error of taking the light at infinity.
  static constexpr double kMaxRelativeBound = 0.25;
  // Two rays missing each other by more than this many of the miss's own sigmas: a highlight
  // is not where the light's reflection is (3 sigma: 3 in 1000 good pairs refused).
  static constexpr double kMaxMissSigmas = 3.0;
};

struct NearLightPosition {
  bool trusted = false;
  Vec3 position{0, 0, 0};   // px, frame coordinates; {0,0,0} when the rays are parallel
  double distancePx = 0;    // |X|; 0 when the rays are parallel (a light at infinity)
  Vec3 direction{0, 0, 1};  // X / |X|; the rays' mean direction when they are parallel
  double covariance[3][3] = {{0, 0, 0}, {0, 0, 0}, {0, 0, 0}};  // of X, px^2
  double distanceBoundPx = 0;   // 95 %: |(|X| - |X_true|)| under it 95 times in 100
  double directionBoundDeg = 0; // 95 %: the angle between X / |X| and the truth's
  double meetAngleDeg = 0;      // the largest angle between two of the rays
  double missPx = 0;            // the largest distance between two rays at their closest
  double missBoundPx = 0;       // what the inputs' covariance allows for it (kMaxMissSigmas sigma)
  std::string reason;   // why not trusted, for a user; empty when trusted
  std::string summary;  // the figures in one sentence, for the record
};

// A sphere's centre, and the mirror point and reflected direction of a highlight on it.
Vec3 sphereCentreInFrame(const DetectedSphere& sphere, int width, int height);
void mirrorRay(const DetectedSphere& sphere, double hx, double hy, int width, int height, Vec3& point,
               Vec3& direction);

// The light's position from two or more spheres' evidence (usable highlights), with the model's
// input covariances (light_uncertainty.h). `sphereNumbers` names the spheres in the reason
// (their index in the capture); empty: 0, 1, ... Fewer than two: Error(Internal).
NearLightPosition positionFromSpheres(const std::vector<SphereEvidence>& evidence, int width, int height,
                                      const std::vector<int>& sphereNumbers = {});
// The same with each sphere's inputs' covariance given (px^2, order hx, hy, cx, cy, r) and the
// floor on each ray's direction (degrees, 1 sigma per axis; 0: none): the propagation alone.
NearLightPosition positionFromSpheres(const std::vector<SphereEvidence>& evidence, int width, int height,
                                      const std::vector<std::array<std::array<double, 5>, 5>>& inputs,
                                      double floorDeg, const std::vector<int>& sphereNumbers = {});

// The point at `distancePx` from the frame's centre along the ray that sphere's highlight
// reflects: from its mirror point P (where the sphere's normal bisects V and `direction`, the
// light's unit direction as seen from that sphere) along `direction`:
//     |P + t L| = d  =>  t = -P.L + sqrt((P.L)^2 - |P|^2 + d^2)
// One root t >= 0 whenever d >= |P|. When the mirror point lies farther from the frame's centre
// than d (a stated distance shorter than the sphere's own: the statement is wrong) there is no
// such light in front of the sphere: ok false and the reason says so.
struct PositionAtDistance {
  bool ok = false;
  Vec3 position{0, 0, 0};
  std::string reason;
};
PositionAtDistance positionAtDistance(const DetectedSphere& sphere, const Vec3& direction, double distancePx,
                                      int width, int height);

// A light's direction from its position (X / |X|, unit) and back (distance times direction).
// A position at the origin has no direction: Error(Internal).
Vec3 directionOfPosition(const Vec3& position);
Vec3 positionOfDirection(const Vec3& direction, double distancePx);

}  // namespace surrogate::hrti
