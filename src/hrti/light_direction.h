// Light direction from a highlight on a mirror sphere (docs/hrti-math.md, corrected formulas).
//
// Orthographic camera (V = (0, 0, 1)): the sphere's normal at the highlight is the half
// vector between V and the light L, so
//     nx = (hx - cx) / r,   ny = -(hy - cy) / r,   nz = sqrt(1 - nx^2 - ny^2)
//     L  = 2 (N.V) N - V = (2 nz nx, 2 nz ny, 2 nz^2 - 1)          (unit by construction)
//     elevation = asin(lz),  azimuth = atan2(ly, lx)
//
// Perspective camera (focal length f, pixel pitch s, principal point (px, py)): pixel (u, v)
// sees along the ray d(u, v) = normalize(((u - px) s, -(v - py) s, -f)). The sphere's image
// circle gives the direction c of its centre (ray through the circle centre) and its angular
// radius a (half the angle between the rays through the circle's two extreme points along
// the line through the principal point), so with the sphere's radius R = 1 its centre is
// C = c / sin(a). The ray through the highlight meets the sphere first at P; there
//     N = P - C,   V = -d,   L = 2 (N.V) N - V.
// As f grows the rays become parallel and the result tends to the orthographic one.
#pragma once

#include "hrti/sphere_detection.h"

namespace surrogate::hrti {

struct LightDirection {
  double x = 0, y = 0, z = 1;  // unit; x right, y up, z towards the camera
  double elevationDeg = 90, azimuthDeg = 0;
};

struct CameraIntrinsics {
  double focalLengthMm = 0;
  double pixelPitchMm = 0;
  double principalX = 0, principalY = 0;  // pixels
};

LightDirection lightFromHighlight(const DetectedSphere& sphere, double hx, double hy);
LightDirection lightFromHighlightPerspective(const DetectedSphere& sphere, double hx, double hy,
                                             const CameraIntrinsics& camera);

// The unit-length ray through pixel (u, v), and the sphere's centre for radius 1 (internal to
// the perspective model and light positions; exposed for tests).
void pixelRay(const CameraIntrinsics& camera, double u, double v, double out[3]);
void sphereCentre(const DetectedSphere& sphere, const CameraIntrinsics& camera, double radius, double out[3]);

LightDirection makeDirection(double x, double y, double z);

}  // namespace surrogate::hrti
