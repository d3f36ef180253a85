// Shared by the light-position tests (test_light_position*.cpp): a light's highlight on a sphere
// found without the code under test, and portable Gaussian noise.
#pragma once

#include <cmath>
#include <cstdint>
#include <random>

#include "hrti/light_position.h"

namespace surrogate::hrti::test {

inline double dot(const Vec3& a, const Vec3& b) { return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]; }
inline double norm(const Vec3& a) { return std::sqrt(dot(a, a)); }

// The highlight of a light at x (frame coordinates of a width x height frame) on a sphere
// resting on the plane: the mirror point's normal lies in the plane of V and x - C, at the angle
// a from V where it bisects V and the direction to x from the point itself; bisection on a.
inline Highlight mirrorHighlight(const DetectedSphere& s, const Vec3& x, int width, int height) {
  const Vec3 c{s.cx - (width - 1) / 2.0, (height - 1) / 2.0 - s.cy, s.r};
  const Vec3 w{x[0] - c[0], x[1] - c[1], x[2] - c[2]};
  const double across = std::hypot(w[0], w[1]);
  const double sx = w[0] / across, sy = w[1] / across;
  double lo = 0, hi = std::atan2(across, w[2]);
  for (int i = 0; i < 200; ++i) {
    const double a = (lo + hi) / 2;
    const Vec3 n{std::sin(a) * sx, std::sin(a) * sy, std::cos(a)};
    const Vec3 d{x[0] - c[0] - s.r * n[0], x[1] - c[1] - s.r * n[1], x[2] - c[2] - s.r * n[2]};
    (n[2] - dot(n, d) / norm(d) > 0 ? lo : hi) = a;  // > 0 while the normal leans towards V
  }
  Highlight h;
  h.x = s.cx + s.r * std::sin((lo + hi) / 2) * sx;
  h.y = s.cy - s.r * std::sin((lo + hi) / 2) * sy;
  h.flag = HighlightFlag::Ok;
  h.confidence = 1;
  return h;
}

// Portable normal deviates (Box-Muller on mt19937's 32-bit output).
struct Noise {
  std::mt19937 rng;
  explicit Noise(std::uint32_t seed) : rng(seed) {}
  double uniform() { return (rng() + 0.5) / 4294967296.0; }
  double normal() { return std::sqrt(-2 * std::log(uniform())) * std::cos(2 * M_PI * uniform()); }
};

}  // namespace surrogate::hrti::test
