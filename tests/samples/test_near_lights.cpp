// Near lights in the generator (issue 53): the rendered shots against closed forms computed
// here from the truth alone, in the frame coordinates of capture_generator.h (origin at image
// point ((W-1)/2, (H-1)/2) on the plane, X right, Y up, Z towards the camera).
#include <catch2/catch.hpp>

#include <algorithm>
#include <array>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "core/error.h"
#include "generator/capture_generator.h"
#include "generator/scene.h"
#include "image/decode.h"

using namespace surrogate;
namespace fs = std::filesystem;

namespace {

using Vec = std::array<double, 3>;

double dot(const Vec& a, const Vec& b) { return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]; }
Vec unit(const Vec& a) {
  const double n = std::sqrt(dot(a, a));
  return {a[0] / n, a[1] / n, a[2] / n};
}

generator::GeneratorOptions nearScene() {
  generator::GeneratorOptions o;
  o.images = 6;
  o.width = 320;
  o.height = 240;
  o.sphereRadius = 40;
  o.seed = 11;
  o.lightDistance = 1.5;  // 480 px: the direction changes by tens of degrees across the frame
  return o;
}

// The point of pixel (x, y) at height z, in frame coordinates.
Vec framePoint(const generator::GeneratorOptions& o, double x, double y, double z) {
  return {x - (o.width - 1) / 2.0, (o.height - 1) / 2.0 - y, z};
}

fs::path freshDir(const std::string& name) {
  const fs::path d = fs::temp_directory_path() / ("surrogate-test-near-" + name);
  fs::remove_all(d);
  return d;
}

}  // namespace

TEST_CASE("near lights: the relief's value follows (|X| / |X - p|)^2 and the cosine of its own direction") {
  // Without noise or shadows, a pixel's flash-lit part (the shot less the shot without flash)
  // under the near light, over the same under the light at infinity, is
  //     R = (|X| / |X - p|)^2 cos(n, X - p) / cos(n, X)
  // with n the true normal and p the pixel's point at the relief's height z, the one unknown:
  // fitted per pixel, the closed form must then hold for every shot.
  generator::GeneratorOptions near = nearScene();
  near.noise = 0;
  near.shadows = false;
  generator::GeneratorOptions far = near, ambient = near;
  far.lightDistance = 0;
  const generator::CaptureTruth t = generator::planCapture(near), tf = generator::planCapture(far);
  REQUIRE(t.positions.size() == std::size_t(near.images));
  REQUIRE(tf.positions.empty());
  REQUIRE(t.lights == tf.lights);  // the directions stay those of the far capture
  ambient.noFlashFrame = 0;
  const Image dark = generator::renderShot(ambient, t, 0);
  const Image normals = generator::trueNormals(near, t);
  std::vector<Image> nearShots, farShots;
  for (int i = 0; i < near.images; ++i) {
    nearShots.push_back(generator::renderShot(near, t, i));
    farShots.push_back(generator::renderShot(far, tf, i));
  }
  // The relief's height along a row, up to a constant, from the true normals: they are the
  // height's central differences, slope s_k = (h(k+1) - h(k-1)) / 2 = -nx / nz, whose sum
  // s_1 + ... + s_(x-1) + s_x / 2 telescopes to (h(x-1) + 2 h(x) + h(x+1)) / 4 less a constant.
  const auto slope = [&](int x, int y) {
    Vec n;
    for (int c = 0; c < 3; ++c) n[c] = normals.at(x, y, c) / 65535.0 * 2 - 1;
    return -n[0] / n[2];
  };
  int pixels = 0, compared = 0;
  for (int y = 20; y < near.height - 20; y += 23) {
    double least = 1e9, most = -1e9;  // the fitted height less the integrated one along this row
    for (int x = 20; x < near.width - 20; x += 23) {
      bool onSphere = false;
      for (const auto& s : t.spheres) onSphere = onSphere || std::hypot(x - s.cx, y - s.cy) < s.r + 6;
      if (onSphere) continue;
      Vec n;
      for (int c = 0; c < 3; ++c) n[c] = normals.at(x, y, c) / 65535.0 * 2 - 1;
      n = unit(n);
      struct Sample { Vec x; double ratio; };
      std::vector<Sample> samples;
      for (int i = 0; i < near.images; ++i) {
        const double a = dark.at(x, y, 1), vn = nearShots[i].at(x, y, 1) - a, vf = farShots[i].at(x, y, 1) - a;
        if (vf < 2000 || nearShots[i].at(x, y, 1) > 60000 || farShots[i].at(x, y, 1) > 60000) continue;
        samples.push_back({t.positions[i], vn / vf});
      }
      if (samples.size() < 3) continue;
      const auto worst = [&](double z) {
        double w = 0;
        for (const Sample& s : samples) {
          const Vec p = framePoint(near, x, y, z), d = {s.x[0] - p[0], s.x[1] - p[1], s.x[2] - p[2]};
          const double model = dot(s.x, s.x) / dot(d, d) * dot(n, unit(d)) / dot(n, unit(s.x));
          w = std::max(w, std::abs(s.ratio / model - 1));
        }
        return w;
      };
      double bestZ = 0, best = 1e9;
      for (double z = -10; z <= 60; z += 0.02)
        if (const double w = worst(z); w < best) best = w, bestZ = z;
      INFO("pixel " << x << "," << y << ": height " << bestZ << ", " << samples.size() << " shots");
      CHECK(best < 0.004);
      CHECK(bestZ > -3);  // the relief's strokes dig 1.5 px at most, its bumps rise 0.15 * 240
      CHECK(bestZ < 40);
      ++pixels;
      bool crossesSphere = false;
      for (const auto& s : t.spheres) crossesSphere = crossesSphere || std::abs(y - s.cy) < s.r + 2;
      if (crossesSphere) continue;
      double integrated = slope(x, y) / 2;
      for (int k = 1; k < x; ++k) integrated += slope(k, y);
      least = std::min(least, bestZ - integrated);
      most = std::max(most, bestZ - integrated);
      ++compared;
    }
    // The same constant along the row: the light saw each point at the relief's own height.
    INFO("row " << y << ": fitted less integrated height from " << least << " to " << most);
    if (most >= least) CHECK(most - least < 0.5);  // 0.1 px here; heights ignored: 2 to 6 px
  }
  CHECK(pixels > 60);
  CHECK(compared > 40);
}

TEST_CASE("near lights: a sphere's highlight is where its normal bisects the view and that point's own light direction") {
  generator::GeneratorOptions o = nearScene();
  o.spheres = 2;
  o.sphereSeparation = 150;
  const generator::CaptureTruth t = generator::planCapture(o);
  REQUIRE(t.spheres.size() == 2);
  const generator::Scene scene(o, t);
  int shifted = 0;
  for (int i = 0; i < o.images; ++i) {
    const Image im = generator::renderShot(scene, o, t, i);
    const generator::ShotLight shot = scene.shotLight(i);  // where the glare streaks start
    const Vec& x = t.positions[i];
    for (std::size_t k = 0; k < t.spheres.size(); ++k) {
      const auto& s = t.spheres[k];
      // The mirror point lies in the vertical plane through the centre C and the light:
      // N(a) = (cos a u, sin a). Bisection on a for N = normalize(V + normalize(X - C - r N)).
      const Vec c = framePoint(o, s.cx, s.cy, s.r);
      const double hx = x[0] - c[0], hy = x[1] - c[1], hl = std::hypot(hx, hy), ux = hx / hl, uy = hy / hl;
      const auto gap = [&](double a) {
        const Vec nrm = {std::cos(a) * ux, std::cos(a) * uy, std::sin(a)};
        const Vec l = unit({x[0] - c[0] - s.r * nrm[0], x[1] - c[1] - s.r * nrm[1], x[2] - c[2] - s.r * nrm[2]});
        const Vec h = unit({l[0], l[1], l[2] + 1});
        return a - std::atan2(h[2], h[0] * ux + h[1] * uy);
      };
      double lo = 0, hi = M_PI / 2;
      for (int k = 0; k < 80; ++k) (gap((lo + hi) / 2) < 0 ? lo : hi) = (lo + hi) / 2;
      const double a = (lo + hi) / 2;
      const double ex = s.cx + s.r * std::cos(a) * ux, ey = s.cy - s.r * std::cos(a) * uy;
      // Where a light at infinity along X / |X| would put it.
      const Vec hf = unit({t.lights[i][0], t.lights[i][1], t.lights[i][2] + 1});
      const double fx = s.cx + s.r * hf[0], fy = s.cy - s.r * hf[1];
      double sx = 0, sy = 0, sw = 0;
      for (int py = 0; py < o.height; ++py)
        for (int px = 0; px < o.width; ++px) {
          if (std::hypot(px - s.cx, py - s.cy) > s.r - 1) continue;
          const double v = im.at(px, py, 1);
          if (v < 60000) continue;
          sx += v * px;
          sy += v * py;
          sw += v;
        }
      INFO("shot " << i << ", sphere at " << s.cx << "," << s.cy << ": expected " << ex << "," << ey << ", far " << fx << "," << fy);
      REQUIRE(sw > 0);
      CHECK(std::hypot(sx / sw - ex, sy / sw - ey) < 0.5);
      CHECK(std::hypot(shot.highlights[k][0] - ex, shot.highlights[k][1] - ey) < 1e-6);
      if (std::hypot(fx - ex, fy - ey) > 2) ++shifted;
    }
  }
  CHECK(shifted >= o.images);  // the per-point direction moved most highlights by pixels
}

TEST_CASE("near lights: the truth files give the positions and the true normals as normals.png encodes them") {
  generator::GeneratorOptions o = nearScene();
  o.images = 2;
  o.formats = generator::OutputFormats::Jpeg;
  const fs::path dir = freshDir("truth");
  generator::writeCapture(o, dir);
  const generator::CaptureTruth t = generator::planCapture(o);

  std::ifstream in(dir / "truth/light-positions.txt");
  std::string line;
  REQUIRE(std::getline(in, line));
  CHECK(line.rfind("# file X Y Z", 0) == 0);
  for (int i = 0; i < o.images; ++i) {
    REQUIRE(std::getline(in, line));
    std::istringstream fields(line);
    std::string file;
    double x, y, z, distance;
    REQUIRE(fields >> file >> x >> y >> z >> distance);
    CHECK(file == "jpeg-exports/IMG_000" + std::to_string(i + 1) + ".jpg");
    const double d = o.lightDistance * o.width;
    CHECK(x == Approx(d * t.lights[i][0]).margin(1e-5));
    CHECK(y == Approx(d * t.lights[i][1]).margin(1e-5));
    CHECK(z == Approx(d * t.lights[i][2]).margin(1e-5));
    CHECK(distance == Approx(o.lightDistance).epsilon(1e-8));
  }
  std::ifstream generatorTxt(dir / "truth/generator.txt");
  const std::string options((std::istreambuf_iterator<char>(generatorTxt)), std::istreambuf_iterator<char>());
  CHECK(options.find("light-distance 1.5\n") != std::string::npos);

  const Image normals = image::decodeImage(dir / "truth/normals.png", image::RawDecodeSettings());
  REQUIRE(normals.width == o.width);
  REQUIRE(normals.height == o.height);
  REQUIRE(normals.channels == 3);
  CHECK(normals.bitsPerSample == 16);
  // A sphere pixel: the sphere's normal at the pixel's centre, value = round((n + 1) / 2 * 65535).
  const auto& s = t.spheres[0];
  const int px = static_cast<int>(std::lround(s.cx - 0.45 * s.r)), py = static_cast<int>(std::lround(s.cy + 0.3 * s.r));
  const double nx = (px - s.cx) / s.r, ny = (s.cy - py) / s.r, nz = std::sqrt(1 - nx * nx - ny * ny);
  CHECK(normals.at(px, py, 0) == std::lround((nx + 1) / 2 * 65535));
  CHECK(normals.at(px, py, 1) == std::lround((ny + 1) / 2 * 65535));
  CHECK(normals.at(px, py, 2) == std::lround((nz + 1) / 2 * 65535));
  CHECK(nx < -0.4);  // left and down on the sphere: x negative, y (up) negative
  CHECK(ny < -0.25);
  // Relief pixels: unit normals facing the camera.
  for (int y = 10; y < o.height; y += 37)
    for (int x = 10; x < o.width / 2; x += 41) {
      Vec n;
      for (int c = 0; c < 3; ++c) n[c] = normals.at(x, y, c) / 65535.0 * 2 - 1;
      CHECK(std::sqrt(dot(n, n)) == Approx(1).margin(1e-4));
      CHECK(n[2] > 0.5);
    }
  fs::remove_all(dir);
}

TEST_CASE("near lights far away render as lights at infinity, and impossible placements are refused") {
  generator::GeneratorOptions far = nearScene(), near = far;
  far.lightDistance = 0;
  far.noise = near.noise = 0;
  far.images = near.images = 2;
  near.lightDistance = 1e6;
  const generator::CaptureTruth tf = generator::planCapture(far), tn = generator::planCapture(near);
  const Image a = generator::renderShot(far, tf, 1), b = generator::renderShot(near, tn, 1);
  int most = 0;
  for (std::size_t i = 0; i < a.pixels.size(); ++i) most = std::max(most, std::abs(int(a.pixels[i]) - int(b.pixels[i])));
  CHECK(most <= 2);

  generator::GeneratorOptions o = nearScene();
  o.spheres = 2;
  o.sphereSeparation = 120;
  const generator::CaptureTruth t = generator::planCapture(o);
  CHECK(t.spheres[1].cy == t.spheres[0].cy);
  CHECK(t.spheres[0].cx - t.spheres[1].cx == Approx(120));
  o.sphereSeparation = 60;  // the discs would overlap
  CHECK_THROWS_AS(generator::planCapture(o), Error);
  o.sphereSeparation = 300;  // out of a frame 320 px wide
  CHECK_THROWS_AS(generator::planCapture(o), Error);
  o.spheres = 1;
  o.sphereSeparation = 120;
  CHECK_THROWS_AS(generator::planCapture(o), Error);
  o = nearScene();
  o.lightDistance = 0.5;
  CHECK_THROWS_AS(generator::planCapture(o), Error);
}
