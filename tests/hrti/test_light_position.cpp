// Light positions from two spheres in frame coordinates (hrti/light_position.h, second part):
// against lights placed by hand and mirror points found by an independent search, the
// uncertainty's 95 % bounds against Monte Carlo, and the verdict on parallel or missing rays.
#include <catch2/catch.hpp>

#include <cmath>
#include <cstdint>
#include <random>
#include <string>

#include "hrti/light_position.h"
#include "mirror_point.h"

using namespace surrogate::hrti;

namespace {

constexpr int kW = 1200, kH = 900;
constexpr double kR = 80;

Vec3 sub(const Vec3& a, const Vec3& b) { return {a[0] - b[0], a[1] - b[1], a[2] - b[2]}; }
using test::dot;
using test::norm;
Vec3 unit(const Vec3& a) {
  const double n = norm(a);
  return {a[0] / n, a[1] / n, a[2] / n};
}

DetectedSphere sphereAt(double cx, double cy) {
  DetectedSphere s;
  s.cx = cx, s.cy = cy, s.r = kR, s.confidence = 1, s.evidence = 1;
  return s;
}

// The light at `d` frame widths, elevation and azimuth in degrees (azimuth 0: +x).
Vec3 lightAt(double d, double elevationDeg, double azimuthDeg) {
  const double e = elevationDeg * M_PI / 180, a = azimuthDeg * M_PI / 180;
  return {d * kW * std::cos(e) * std::cos(a), d * kW * std::cos(e) * std::sin(a), d * kW * std::sin(e)};
}

Highlight highlightOf(const DetectedSphere& s, const Vec3& x) { return test::mirrorHighlight(s, x, kW, kH); }
using test::Noise;

double angleDeg(const Vec3& a, const Vec3& b) {
  return std::acos(std::min(1.0, dot(unit(a), unit(b)))) * 180 / M_PI;
}

}  // namespace

TEST_CASE("positionFromSpheres places a light where it is, from exact highlights", "[light-position]") {
  const std::vector<DetectedSphere> spheres = {sphereAt(300, 700), sphereAt(900, 700)};
  for (double d : {1.5, 3.0, 4.0})
    for (double elevation : {15.0, 45.0, 75.0})
      for (double azimuth : {0.0, 60.0, 135.0, 250.0}) {
        const Vec3 x = lightAt(d, elevation, azimuth);
        std::vector<SphereEvidence> e;
        for (const DetectedSphere& s : spheres) e.push_back({s, highlightOf(s, x)});
        const NearLightPosition p = positionFromSpheres(e, kW, kH);
        INFO("D " << d << " elevation " << elevation << " azimuth " << azimuth << ": " << p.summary);
        CHECK(norm(sub(p.position, x)) < 1e-6 * norm(x));
        CHECK(p.distancePx == Approx(d * kW).epsilon(1e-6));
        CHECK(angleDeg(p.direction, x) < 1e-6);
        CHECK(p.missPx < 1e-6 * norm(x));
        // Each sphere's own ray, continued to the light's distance, reaches it.
        for (const SphereEvidence& s : e) {
          Vec3 point, l;
          mirrorRay(s.sphere, s.highlight.x, s.highlight.y, kW, kH, point, l);
          const PositionAtDistance a = positionAtDistance(s.sphere, l, d * kW, kW, kH);
          REQUIRE(a.ok);
          CHECK(norm(sub(a.position, x)) < 1e-6 * norm(x));
        }
      }
  // Well placed: D = 3 at 45 degrees, the spheres 600 px apart across the light: trusted.
  const Vec3 x = lightAt(3, 45, 90);
  const NearLightPosition p =
      positionFromSpheres({{spheres[0], highlightOf(spheres[0], x)}, {spheres[1], highlightOf(spheres[1], x)}}, kW, kH);
  INFO(p.summary);
  CHECK(p.trusted);
  CHECK(p.reason.empty());
  CHECK(p.distanceBoundPx > 0);
  CHECK(p.distanceBoundPx < 0.25 * p.distancePx);
}

TEST_CASE("Light positions and directions convert both ways", "[light-position]") {
  const Vec3 x{-1234.5, 2345.25, 3000};
  const Vec3 u = directionOfPosition(x);
  CHECK(norm(u) == Approx(1).epsilon(1e-15));
  const Vec3 back = positionOfDirection(u, norm(x));
  CHECK(norm(sub(back, x)) < 1e-9);
  CHECK_THROWS(directionOfPosition({0, 0, 0}));
  // A sphere centred at the frame's centre: the ray from its top point along V reaches (0, 0, D W).
  const PositionAtDistance top = positionAtDistance(sphereAt((kW - 1) / 2.0, (kH - 1) / 2.0), {0, 0, 1}, 3600, kW, kH);
  REQUIRE(top.ok);
  CHECK(top.position[2] == Approx(3600).epsilon(1e-12));
  // A stated distance shorter than the sphere's own distance from the centre: no light there.
  const PositionAtDistance none = positionAtDistance(sphereAt(1100, 100), unit({1, 1, 1}), 500, kW, kH);
  CHECK_FALSE(none.ok);
  CHECK(none.reason.find("shorter than the distance of the sphere") != std::string::npos);
}

TEST_CASE("The 95 % bounds of a light's position cover its errors 95 times in 100", "[light-position]") {
  // Highlights and circles with Gaussian errors of known size, given as the inputs' covariance
  // (no floor): the bounds are the propagation's, the errors the Monte Carlo's.
  const std::vector<DetectedSphere> spheres = {sphereAt(300, 700), sphereAt(900, 700)};
  struct Case {
    double d, elevation, azimuth, highlightPx, circlePx;
  };
  for (const Case& c : {Case{3, 45, 90, 0.2, 0}, Case{1.5, 30, 20, 0.3, 0.2}, Case{4, 60, 200, 0.2, 0.1}}) {
    const Vec3 x = lightAt(c.d, c.elevation, c.azimuth);
    std::vector<Highlight> truth;
    for (const DetectedSphere& s : spheres) truth.push_back(highlightOf(s, x));
    std::array<std::array<double, 5>, 5> cov{};
    cov[0][0] = cov[1][1] = c.highlightPx * c.highlightPx;
    cov[2][2] = cov[3][3] = cov[4][4] = c.circlePx * c.circlePx;
    Noise noise(53);
    const int kTrials = 400;
    int distanceIn = 0, directionIn = 0;
    for (int t = 0; t < kTrials; ++t) {
      std::vector<SphereEvidence> e;
      for (std::size_t k = 0; k < spheres.size(); ++k) {
        DetectedSphere s = spheres[k];
        s.cx += c.circlePx * noise.normal(), s.cy += c.circlePx * noise.normal(), s.r += c.circlePx * noise.normal();
        Highlight h = truth[k];
        h.x += c.highlightPx * noise.normal(), h.y += c.highlightPx * noise.normal();
        e.push_back({s, h});
      }
      const NearLightPosition p = positionFromSpheres(e, kW, kH, {cov, cov}, 0.0);
      distanceIn += std::fabs(p.distancePx - norm(x)) <= p.distanceBoundPx;
      directionIn += angleDeg(p.direction, x) <= p.directionBoundDeg;
    }
    INFO("D " << c.d << " elevation " << c.elevation << ": distance " << distanceIn << ", direction " << directionIn
              << " of " << kTrials);
    CHECK(distanceIn >= 0.91 * kTrials);
    CHECK(distanceIn <= 0.99 * kTrials);
    CHECK(directionIn >= 0.91 * kTrials);
    CHECK(directionIn <= 0.99 * kTrials);
  }
}

TEST_CASE("Parallel, diverging or missing rays give no trusted position, and say why", "[light-position]") {
  const std::vector<DetectedSphere> spheres = {sphereAt(300, 700), sphereAt(900, 700)};
  // A light at infinity: the same highlight on both spheres, parallel rays.
  Highlight h0 = highlightOf(spheres[0], lightAt(1e9, 40, 30));
  Highlight h1 = h0;
  h1.x += spheres[1].cx - spheres[0].cx;
  const NearLightPosition parallel = positionFromSpheres({{spheres[0], h0}, {spheres[1], h1}}, kW, kH, {3, 5});
  CHECK_FALSE(parallel.trusted);
  CHECK(parallel.distancePx == 0);
  CHECK(parallel.reason.find("the rays from spheres 3 and 5 are parallel") != std::string::npos);
  CHECK(angleDeg(parallel.direction, lightAt(1, 40, 30)) < 1e-6);
  // A far light (50 frame widths) along the spheres' baseline: nearly parallel rays.
  const Vec3 far = lightAt(50, 30, 0);
  const NearLightPosition p =
      positionFromSpheres({{spheres[0], highlightOf(spheres[0], far)}, {spheres[1], highlightOf(spheres[1], far)}}, kW, kH);
  INFO(p.reason);
  CHECK_FALSE(p.trusted);
  CHECK(p.reason.find("too parallel to place the light") != std::string::npos);
  // One highlight moved 4 px off its place across the rays' plane: the rays miss each other.
  const Vec3 x = lightAt(3, 45, 90);
  Highlight off = highlightOf(spheres[1], x);
  off.y += 4;
  const NearLightPosition m = positionFromSpheres({{spheres[0], highlightOf(spheres[0], x)}, {spheres[1], off}}, kW, kH);
  INFO(m.reason);
  CHECK_FALSE(m.trusted);
  CHECK(m.reason.find("miss each other") != std::string::npos);
  // The same highlight moved so that the rays diverge: nearest behind the spheres.
  Highlight apart = highlightOf(spheres[1], lightAt(50, 45, 0));
  apart.x += 3;
  const NearLightPosition b =
      positionFromSpheres({{spheres[0], highlightOf(spheres[0], lightAt(50, 45, 0))}, {spheres[1], apart}}, kW, kH);
  INFO(b.reason);
  CHECK_FALSE(b.trusted);
  CHECK(b.reason.find("diverge") != std::string::npos);
}
