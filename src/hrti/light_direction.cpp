#include "hrti/light_direction.h"

#include <algorithm>
#include <cmath>

namespace surrogate::hrti {

LightDirection makeDirection(double x, double y, double z) {
  const double n = std::sqrt(x * x + y * y + z * z);
  LightDirection l;
  l.x = x / n;
  l.y = y / n;
  l.z = z / n;
  l.elevationDeg = std::asin(std::clamp(l.z, -1.0, 1.0)) * 180 / M_PI;
  l.azimuthDeg = std::atan2(l.y, l.x) * 180 / M_PI;
  return l;
}

LightDirection lightFromHighlight(const DetectedSphere& s, double hx, double hy) {
  double nx = (hx - s.cx) / s.r, ny = -(hy - s.cy) / s.r;
  const double d = nx * nx + ny * ny;
  if (d > 1) {  // a centroid just outside the fitted circle: clamp onto the outline
    nx /= std::sqrt(d);
    ny /= std::sqrt(d);
  }
  const double nz = std::sqrt(std::max(0.0, 1 - nx * nx - ny * ny));
  return makeDirection(2 * nz * nx, 2 * nz * ny, 2 * nz * nz - 1);
}

void pixelRay(const CameraIntrinsics& c, double u, double v, double out[3]) {
  const double x = (u - c.principalX) * c.pixelPitchMm, y = -(v - c.principalY) * c.pixelPitchMm, z = -c.focalLengthMm;
  const double n = std::sqrt(x * x + y * y + z * z);
  out[0] = x / n;
  out[1] = y / n;
  out[2] = z / n;
}

void sphereCentre(const DetectedSphere& s, const CameraIntrinsics& c, double radius, double out[3]) {
  // The circle's extreme points along the line from the principal point through its centre.
  double ux = s.cx - c.principalX, uy = s.cy - c.principalY;
  const double len = std::hypot(ux, uy);
  if (len < 1e-9) {
    ux = 1;
    uy = 0;
  } else {
    ux /= len;
    uy /= len;
  }
  double a[3], b[3], centre[3];
  pixelRay(c, s.cx - s.r * ux, s.cy - s.r * uy, a);
  pixelRay(c, s.cx + s.r * ux, s.cy + s.r * uy, b);
  const double cosAngle = std::clamp(a[0] * b[0] + a[1] * b[1] + a[2] * b[2], -1.0, 1.0);
  const double half = std::acos(cosAngle) / 2;
  // The centre lies on the bisector of the two tangent rays.
  for (int k = 0; k < 3; ++k) centre[k] = a[k] + b[k];
  const double n = std::sqrt(centre[0] * centre[0] + centre[1] * centre[1] + centre[2] * centre[2]);
  const double distance = radius / std::sin(half);
  for (int k = 0; k < 3; ++k) out[k] = centre[k] / n * distance;
}

LightDirection lightFromHighlightPerspective(const DetectedSphere& s, double hx, double hy,
                                             const CameraIntrinsics& c) {
  double centre[3], d[3];
  sphereCentre(s, c, 1.0, centre);
  pixelRay(c, hx, hy, d);
  // Ray-sphere intersection: |t d - C|^2 = 1, nearest t.
  const double b = d[0] * centre[0] + d[1] * centre[1] + d[2] * centre[2];
  const double cc = centre[0] * centre[0] + centre[1] * centre[1] + centre[2] * centre[2] - 1;
  const double t = b - std::sqrt(std::max(0.0, b * b - cc));
  double n[3], v[3];
  for (int k = 0; k < 3; ++k) {
    n[k] = t * d[k] - centre[k];
    v[k] = -d[k];
  }
  const double nn = std::sqrt(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]);
  for (double& x : n) x /= nn;
  const double ndotv = n[0] * v[0] + n[1] * v[1] + n[2] * v[2];
  return makeDirection(2 * ndotv * n[0] - v[0], 2 * ndotv * n[1] - v[1], 2 * ndotv * n[2] - v[2]);
}

}  // namespace surrogate::hrti
