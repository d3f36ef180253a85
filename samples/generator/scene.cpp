#include "generator/scene.h"

#include <algorithm>
#include <cmath>

#include "generator/random.h"

namespace surrogate::generator {

namespace {

// Smooth value noise in [0, 1] at scale `cell` pixels.
double valueNoise(std::uint64_t seed, double x, double y, double cell) {
  const double fx = x / cell, fy = y / cell;
  const long ix = static_cast<long>(std::floor(fx)), iy = static_cast<long>(std::floor(fy));
  const double tx = fx - ix, ty = fy - iy;
  auto corner = [&](long cx, long cy) { return uniform(hash3(seed, static_cast<std::uint64_t>(cx), static_cast<std::uint64_t>(cy))); };
  auto smooth = [](double t) { return t * t * (3 - 2 * t); };
  const double a = corner(ix, iy), b = corner(ix + 1, iy), c = corner(ix, iy + 1), d = corner(ix + 1, iy + 1);
  const double sx = smooth(tx), sy = smooth(ty);
  return (a * (1 - sx) + b * sx) * (1 - sy) + (c * (1 - sx) + d * sx) * sy;
}

double segmentDistance(double px, double py, double ax, double ay, double bx, double by) {
  const double vx = bx - ax, vy = by - ay;
  const double t = std::clamp(((px - ax) * vx + (py - ay) * vy) / (vx * vx + vy * vy), 0.0, 1.0);
  return std::hypot(px - (ax + t * vx), py - (ay + t * vy));
}

}  // namespace

Scene::Scene(const GeneratorOptions& o, const CaptureTruth& t) : o_(o), t_(t), w_(o.width), h_(o.height) {
  const std::size_t n = std::size_t(w_) * h_;
  height_.resize(n);
  normal_.resize(n);
  albedo_.resize(n);
  const double scale = std::min(w_, h_);
  // A few bumps and engraved strokes, placed from the seed.
  struct Bump { double x, y, s, a; };
  std::vector<Bump> bumps;
  for (int k = 0; k < 5; ++k) {
    const std::uint64_t hsh = hash3(o.seed, 101, k);
    bumps.push_back({uniform(mix64(hsh)) * w_, uniform(mix64(hsh + 1)) * h_,
                     scale * (0.08 + 0.12 * uniform(mix64(hsh + 2))), scale * (0.01 + 0.02 * uniform(mix64(hsh + 3)))});
  }
  struct Stroke { double ax, ay, bx, by; };
  std::vector<Stroke> strokes;
  for (int k = 0; k < 12; ++k) {
    const std::uint64_t hsh = hash3(o.seed, 202, k);
    const double ax = (0.1 + 0.6 * uniform(mix64(hsh))) * w_, ay = (0.45 + 0.45 * uniform(mix64(hsh + 1))) * h_;
    const double ang = 2 * M_PI * uniform(mix64(hsh + 2)), len = scale * (0.05 + 0.1 * uniform(mix64(hsh + 3)));
    strokes.push_back({ax, ay, ax + len * std::cos(ang), ay + len * std::sin(ang)});
  }
  const double strokeWidth = std::max(1.5, scale * 0.006), strokeDepth = std::max(1.5, scale * 0.005);
  for (int y = 0; y < h_; ++y) {
    for (int x = 0; x < w_; ++x) {
      double hgt = 0;
      for (const Bump& b : bumps) hgt += b.a * std::exp(-((x - b.x) * (x - b.x) + (y - b.y) * (y - b.y)) / (2 * b.s * b.s));
      for (const Stroke& s : strokes) {
        const double d = segmentDistance(x, y, s.ax, s.ay, s.bx, s.by);
        if (d < 3 * strokeWidth) hgt -= strokeDepth * std::exp(-d * d / (2 * strokeWidth * strokeWidth));
      }
      hgt += 0.8 * valueNoise(o.seed + 1, x, y, 6) + 0.4 * valueNoise(o.seed + 2, x, y, 2.5);
      height_[std::size_t(y) * w_ + x] = static_cast<float>(hgt);
      maxHeight_ = std::max(maxHeight_, hgt);
      double tone = 0.75 + 0.25 * valueNoise(o.seed + 3, x, y, scale * 0.05);
      if (o.strongTexture) {
        const bool stripe = (static_cast<long>(std::floor((x + 0.5 * y) / (scale * 0.03))) & 1) != 0;
        tone *= stripe ? 1.0 : 0.35;
      }
      const double tint = valueNoise(o.seed + 4, x, y, scale * 0.1);
      albedo_[std::size_t(y) * w_ + x] = {static_cast<float>(tone * (0.62 + 0.1 * tint)),
                                          static_cast<float>(tone * 0.50),
                                          static_cast<float>(tone * (0.38 - 0.08 * tint))};
    }
  }
  for (int y = 0; y < h_; ++y) {
    for (int x = 0; x < w_; ++x) {
      const double dx = (height(std::min(x + 1, w_ - 1), y) - height(std::max(x - 1, 0), y)) / 2;
      const double dy = (height(x, std::min(y + 1, h_ - 1)) - height(x, std::max(y - 1, 0))) / 2;
      // Height rises with +dy in image rows (down) = -Y in the camera frame.
      const double nx = -dx, ny = dy, nz = 1, len = std::sqrt(nx * nx + ny * ny + nz * nz);
      normal_[std::size_t(y) * w_ + x] = {static_cast<float>(nx / len), static_cast<float>(ny / len), static_cast<float>(nz / len)};
    }
  }
}

bool Scene::shadowedByRelief(int x, int y, const std::array<double, 3>& l) const {
  const double horizontal = std::hypot(l[0], l[1]);
  if (horizontal < 1e-9) return false;
  const double stepX = l[0] / horizontal, stepY = -l[1] / horizontal;  // image y is down
  const double rise = l[2] / horizontal;                                // height gained per pixel
  const double start = height(x, y);
  const int maxSteps = static_cast<int>(std::min(400.0, (maxHeight_ - start) / std::max(rise, 1e-6) + 2));
  for (int s = 1; s <= maxSteps; ++s) {
    const int px = static_cast<int>(std::lround(x + s * stepX)), py = static_cast<int>(std::lround(y + s * stepY));
    if (px < 0 || py < 0 || px >= w_ || py >= h_) return false;
    if (height(px, py) > start + s * rise + 0.05) return true;
  }
  return false;
}

bool Scene::shadowedBySphere(double x, double y, double z, const std::array<double, 3>& l) const {
  for (const SphereTruth& s : t_.spheres) {
    // Sphere centre in camera-frame pixel units: (cx, -cy, r) (it rests on the surface).
    const double ox = x - s.cx, oy = -y + s.cy, oz = z - s.r;
    const double b = ox * l[0] + oy * l[1] + oz * l[2];
    const double c = ox * ox + oy * oy + oz * oz - s.r * s.r;
    if (c > 0 && b < 0 && b * b - c > 0) return true;
  }
  return false;
}

bool Scene::sphereRadiance(double sx, double sy, const std::array<double, 3>& l, double* out) const {
  for (const SphereTruth& s : t_.spheres) {
    const double nx = (sx - s.cx) / s.r, ny = -(sy - s.cy) / s.r;
    const double d2 = nx * nx + ny * ny;
    if (d2 >= 1) continue;
    const double nz = std::sqrt(1 - d2);
    const double ndotl = nx * l[0] + ny * l[1] + nz * l[2];
    // Blinn-Phong around the half vector H = normalize(L + V): peak exactly at the mirror point.
    double hx = l[0], hy = l[1], hz = l[2] + 1;
    const double hl = std::sqrt(hx * hx + hy * hy + hz * hz);
    hx /= hl; hy /= hl; hz /= hl;
    const double ndoth = std::max(0.0, nx * hx + ny * hy + nz * hz);
    const double spec = ndotl > 0 ? 6.0 * std::pow(ndoth, 600.0) : 0.0;
    *out = 0.02 * std::max(0.0, ndotl) + 0.004 + spec;
    return true;
  }
  return false;
}

std::array<double, 3> Scene::radiance(int x, int y, const std::array<double, 3>& l) const {
  // Pixels near a sphere's outline are supersampled (4x4) so the edge and the highlight are
  // anti-aliased: detection must then find centres to sub-pixel accuracy.
  bool nearSphere = false;
  for (const SphereTruth& s : t_.spheres)
    nearSphere = nearSphere || std::hypot(x - s.cx, y - s.cy) < s.r + 1.5;
  const std::size_t i = std::size_t(y) * w_ + x;
  const auto& n = normal_[i];
  const auto& a = albedo_[i];
  auto surface = [&]() {
    double lambert = std::max(0.0, n[0] * l[0] + n[1] * l[1] + n[2] * l[2]);
    if (o_.shadows && lambert > 0 && (shadowedByRelief(x, y, l) || shadowedBySphere(x, y, height(x, y), l)))
      lambert = 0;
    const double e = 0.85 * lambert + 0.03;
    return std::array<double, 3>{a[0] * e, a[1] * e, a[2] * e};
  };
  if (!nearSphere) return surface();
  const std::array<double, 3> ground = surface();
  std::array<double, 3> sum{0, 0, 0};
  for (int sy = 0; sy < 4; ++sy) {
    for (int sx = 0; sx < 4; ++sx) {
      double v;
      if (sphereRadiance(x + (sx + 0.5) / 4 - 0.5, y + (sy + 0.5) / 4 - 0.5, l, &v)) {
        for (double& c : sum) c += v;
      } else {
        for (int c = 0; c < 3; ++c) sum[c] += ground[c];
      }
    }
  }
  for (double& c : sum) c /= 16;
  return sum;
}

}  // namespace surrogate::generator
