#include "generator/scene.h"

#include <algorithm>
#include <cmath>

#include "generator/chart.h"
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

// The hard cases' scene (GeneratorOptions, docs/hrti-math.md "Generated hard cases").
// The window: a bright rectangle with a cross of glazing bars, 30 degrees above the horizon on
// the upper left, 36 x 24 degrees; mirrored where a light from there would put its highlight
// (half-way to the view axis: 60 degrees of the sphere's elevation), so the highlights of the
// lights from that side cross it.
constexpr double kWindowElevationDeg = 30, kWindowAzimuthDeg = 120;
constexpr double kWindowHalfWidth = 0.325, kWindowHalfHeight = 0.213;  // tan 18, tan 12 degrees
constexpr double kWindowBarHalfWidth = 0.02;
constexpr double kWindowRadiance = 0.9;  // 72 % of full scale after the exposure: bright, unclipped
constexpr double kRoomRadiance = 0.03;   // the walls and floor, brighter towards the ceiling
// Dust: specks of 0.5-1.5 px radius within 0.8 of the radius, lit mostly by the flash.
constexpr double kDustAmbient = 0.1, kDustLit = 0.6;
// Glare: a streak from the highlight, 0.6 r long (e-folding) on one side and 0.2 r on the other,
// its width r / 60 (at least 0.8 px): the asymmetric smear of a real lens.
constexpr double kGlareLong = 0.6, kGlareShort = 0.2, kGlareWidth = 1.0 / 60;

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
  // The chart (colourChart): flat and level, so its normals are (0, 0, 1) whatever the relief.
  const std::vector<std::uint8_t> flat = t.chart.reference.empty() ? std::vector<std::uint8_t>()
                                                                    : paintChart(t.chart, w_, h_, &height_, &albedo_);
  for (int y = 0; y < h_; ++y) {
    for (int x = 0; x < w_; ++x) {
      const double dx = (height(std::min(x + 1, w_ - 1), y) - height(std::max(x - 1, 0), y)) / 2;
      const double dy = (height(x, std::min(y + 1, h_ - 1)) - height(x, std::max(y - 1, 0))) / 2;
      // Height rises with +dy in image rows (down) = -Y in the camera frame.
      const double nx = -dx, ny = dy, nz = 1, len = std::sqrt(nx * nx + ny * ny + nz * nz);
      normal_[std::size_t(y) * w_ + x] = {static_cast<float>(nx / len), static_cast<float>(ny / len), static_cast<float>(nz / len)};
      if (!flat.empty() && flat[std::size_t(y) * w_ + x]) normal_[std::size_t(y) * w_ + x] = {0, 0, 1};
    }
  }
  for (std::size_t k = 0; k < t.spheres.size(); ++k)
    for (int d = 0; d < o.dustSpecks; ++d) {
      const std::uint64_t hsh = hash3(o.seed, 303 + k, d);
      const double along = 0.8 * t.spheres[k].r * std::sqrt(uniform(mix64(hsh))), angle = 2 * M_PI * uniform(mix64(hsh + 1));
      specks_.push_back({t.spheres[k].cx + along * std::cos(angle), t.spheres[k].cy + along * std::sin(angle),
                         0.5 + uniform(mix64(hsh + 2)), 0.5 + 0.5 * uniform(mix64(hsh + 3))});
    }
  const double we = kWindowElevationDeg * M_PI / 180, wa = kWindowAzimuthDeg * M_PI / 180;
  window_ = {std::cos(we) * std::cos(wa), std::cos(we) * std::sin(wa), std::sin(we)};
  windowU_ = {-std::sin(wa), std::cos(wa), 0};  // horizontal across the window
  windowV_ = {-std::sin(we) * std::cos(wa), -std::sin(we) * std::sin(wa), std::cos(we)};  // up it
  const double glareAngle = M_PI * uniform(hash3(o.seed, 404, 0));
  glareCos_ = std::cos(glareAngle);
  glareSin_ = std::sin(glareAngle);
}

double Scene::environment(double rx, double ry, double rz) const {
  double v = kRoomRadiance * (1 + std::max(-1.0, std::min(1.0, ry))) / 2;
  const double depth = rx * window_[0] + ry * window_[1] + rz * window_[2];
  if (depth > 0) {
    const double a = (rx * windowU_[0] + ry * windowU_[1] + rz * windowU_[2]) / depth;
    const double b = (rx * windowV_[0] + ry * windowV_[1] + rz * windowV_[2]) / depth;
    if (std::abs(a) < kWindowHalfWidth && std::abs(b) < kWindowHalfHeight && std::abs(a) > kWindowBarHalfWidth &&
        std::abs(b) > kWindowBarHalfWidth)
      v = kWindowRadiance;
  }
  return v;
}

ShotLight Scene::shotLight(int index) const {
  ShotLight light;
  const std::array<double, 3>& l = t_.lights.at(index);
  light.direction = l;
  light.near = !t_.positions.empty();
  if (!light.near) {
    double hx = l[0], hy = l[1], hz = l[2] + 1;
    const double hl = std::sqrt(hx * hx + hy * hy + hz * hz);
    for (const SphereTruth& s : t_.spheres) light.highlights.push_back({s.cx + s.r * hx / hl, s.cy - s.r * hy / hl});
    return light;
  }
  const std::array<double, 3>& x = t_.positions.at(index);
  light.position = x;
  light.distanceSquared = x[0] * x[0] + x[1] * x[1] + x[2] * x[2];
  // Each sphere's highlight: the point P = C + r N whose normal bisects V and the direction
  // from P itself to the light. The fixed point of N <- normalize(normalize(X - C - r N) + V)
  // contracts by about r / |X - P| (at most 1/2 with kMinLightDistance): 60 rounds are exact.
  for (const SphereTruth& s : t_.spheres) {
    const std::array<double, 3> c = {s.cx - (w_ - 1) / 2.0, (h_ - 1) / 2.0 - s.cy, s.r};
    std::array<double, 3> n = {0, 0, 1};
    for (int round = 0; round < 60; ++round) {
      std::array<double, 3> d;
      for (int k = 0; k < 3; ++k) d[k] = x[k] - c[k] - s.r * n[k];
      const double dl = std::sqrt(d[0] * d[0] + d[1] * d[1] + d[2] * d[2]);
      std::array<double, 3> hv = {d[0] / dl, d[1] / dl, d[2] / dl + 1};
      const double hl = std::sqrt(hv[0] * hv[0] + hv[1] * hv[1] + hv[2] * hv[2]);
      for (int k = 0; k < 3; ++k) n[k] = hv[k] / hl;
    }
    light.highlights.push_back({s.cx + s.r * n[0], s.cy - s.r * n[1]});
  }
  return light;
}

void Scene::lightAt(const ShotLight& light, double px, double py, double z, std::array<double, 3>* l,
                    double* falloff) const {
  if (!light.near) {
    *l = light.direction;
    *falloff = 1;
    return;
  }
  const double dx = light.position[0] - (px - (w_ - 1) / 2.0), dy = light.position[1] - ((h_ - 1) / 2.0 - py),
               dz = light.position[2] - z;
  const double d2 = dx * dx + dy * dy + dz * dz, d = std::sqrt(d2);
  *l = {dx / d, dy / d, dz / d};
  *falloff = light.distanceSquared / d2;
}

std::array<double, 3> Scene::normal(int x, int y) const {
  for (const SphereTruth& s : t_.spheres) {
    const double nx = (x - s.cx) / s.r, ny = -(y - s.cy) / s.r, d2 = nx * nx + ny * ny;
    if (d2 < 1) return {nx, ny, std::sqrt(1 - d2)};
  }
  const auto& n = normal_[std::size_t(y) * w_ + x];
  return {n[0], n[1], n[2]};
}

double Scene::glare(int x, int y, const ShotLight& light) const {
  double v = 0;
  for (std::size_t k = 0; k < t_.spheres.size(); ++k) {
    const SphereTruth& s = t_.spheres[k];
    const double px = light.highlights[k][0], py = light.highlights[k][1];  // the highlight (mirror point)
    const double along = (x - px) * glareCos_ + (y - py) * glareSin_;
    const double across = -(x - px) * glareSin_ + (y - py) * glareCos_;
    const double width = std::max(0.8, kGlareWidth * s.r);
    const double length = (along >= 0 ? kGlareLong : kGlareShort) * s.r;
    if (std::abs(across) > 5 * width || std::abs(along) > 8 * length) continue;
    // o_.glare is the streak's height at the highlight as a fraction of full scale, which is
    // what the exposure makes of radiance o_.glare / kExposure.
    v += o_.glare / kExposure * std::exp(-across * across / (2 * width * width)) * std::exp(-std::abs(along) / length);
  }
  return v;
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

bool Scene::sphereRadiance(double sx, double sy, const ShotLight& light, bool flash, double* out) const {
  for (const SphereTruth& s : t_.spheres) {
    const double nx = (sx - s.cx) / s.r, ny = -(sy - s.cy) / s.r;
    const double d2 = nx * nx + ny * ny;
    if (d2 >= 1) continue;
    const double nz = std::sqrt(1 - d2);
    std::array<double, 3> l;
    double falloff;
    lightAt(light, sx, sy, s.r + s.r * nz, &l, &falloff);  // the point C + r N, C at height r
    const double ndotl = nx * l[0] + ny * l[1] + nz * l[2];
    for (const Speck& d : specks_)
      if (std::hypot(sx - d.x, sy - d.y) < d.radius) {
        *out = d.brightness * (kDustAmbient + (flash ? kDustLit * std::max(0.0, ndotl) * falloff : 0.0));
        return true;
      }
    // The room mirrored (reflections): the direction the camera sees reflected, 2 (N.V) N - V.
    const double room = o_.reflections ? environment(2 * nz * nx, 2 * nz * ny, 2 * nz * nz - 1) : 0.0;
    if (!flash) {
      *out = 0.004 + room;
      return true;
    }
    // Blinn-Phong around the half vector H = normalize(L + V): peak exactly at the mirror point.
    double hx = l[0], hy = l[1], hz = l[2] + 1;
    const double hl = std::sqrt(hx * hx + hy * hy + hz * hz);
    hx /= hl; hy /= hl; hz /= hl;
    const double ndoth = std::max(0.0, nx * hx + ny * hy + nz * hz);
    const double spec = ndotl > 0 ? 6.0 * std::pow(ndoth, 600.0) * falloff : 0.0;
    *out = 0.02 * std::max(0.0, ndotl) * falloff + 0.004 + spec;
    if (o_.reflections) *out += room;
    return true;
  }
  return false;
}

std::array<double, 3> Scene::radiance(int x, int y, const ShotLight& light, bool flash) const {
  // Pixels near a sphere's outline are supersampled (4x4) so the edge and the highlight are
  // anti-aliased: detection must then find centres to sub-pixel accuracy.
  bool nearSphere = false;
  for (const SphereTruth& s : t_.spheres)
    nearSphere = nearSphere || std::hypot(x - s.cx, y - s.cy) < s.r + 1.5;
  const std::size_t i = std::size_t(y) * w_ + x;
  const auto& n = normal_[i];
  const auto& a = albedo_[i];
  auto surface = [&]() {
    std::array<double, 3> l;
    double falloff;
    lightAt(light, x, y, height(x, y), &l, &falloff);
    double lambert = flash ? std::max(0.0, n[0] * l[0] + n[1] * l[1] + n[2] * l[2]) : 0.0;
    if (o_.shadows && lambert > 0 && (shadowedByRelief(x, y, l) || shadowedBySphere(x, y, height(x, y), l)))
      lambert = 0;
    const double e = 0.85 * lambert * falloff + 0.03;  // falloff 1 at infinity: the same bits
    return std::array<double, 3>{a[0] * e, a[1] * e, a[2] * e};
  };
  const double streak = flash && o_.glare > 0 ? glare(x, y, light) : 0.0;
  if (!nearSphere) {
    std::array<double, 3> v = surface();
    if (streak > 0)
      for (double& c : v) c += streak;
    return v;
  }
  const std::array<double, 3> ground = surface();
  std::array<double, 3> sum{0, 0, 0};
  for (int sy = 0; sy < 4; ++sy) {
    for (int sx = 0; sx < 4; ++sx) {
      double v;
      if (sphereRadiance(x + (sx + 0.5) / 4 - 0.5, y + (sy + 0.5) / 4 - 0.5, light, flash, &v)) {
        for (double& c : sum) c += v;
      } else {
        for (int c = 0; c < 3; ++c) sum[c] += ground[c];
      }
    }
  }
  for (double& c : sum) c /= 16;
  if (streak > 0)
    for (double& c : sum) c += streak;
  return sum;
}

}  // namespace surrogate::generator
