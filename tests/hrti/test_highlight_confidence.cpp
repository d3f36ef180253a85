// Every highlight is judged (hrti/highlight_detection.h): a frame whose sphere shows no
// compact peak far above the sphere's body is refused with a reason, never turned into a
// confident light direction; the generated captures of the tests, benchmarks and demo keep
// confidence 1 with a wide margin to every limit.
#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>

#include "core/stack.h"
#include "generator/capture_generator.h"
#include "hrti/highlight_detection.h"
#include "hrti/sphere_detection.h"
#include "hrti/stack_median.h"

using namespace surrogate;
using namespace surrogate::hrti;

namespace {

const DetectedSphere kSphere{60, 60, 45, 1};

// A 120x120 frame: the sphere's dark body (value `body`, 0..1) with `paint` applied to each
// pixel inside the sphere (d: distance from the centre).
template <typename Paint>
Image sphereFrame(double body, Paint paint) {
  Image im(120, 120, 1);
  for (int y = 0; y < 120; ++y)
    for (int x = 0; x < 120; ++x) {
      double v = body;
      paint(x, y, v);
      im.at(x, y) = static_cast<std::uint16_t>(std::lround(std::clamp(v, 0.0, 1.0) * 65535));
    }
  return im;
}

// A highlight as the generator draws one: a saturated spot with a steep fall-off.
Image goodFrame(double hx = 70, double hy = 50) {
  return sphereFrame(0.03, [&](int x, int y, double& v) {
    const double d = std::hypot(x - hx, y - hy);
    v += 6 * std::exp(-d * d / (2 * 2.5 * 2.5));
  });
}

Highlight detect(const Image& frame) { return detectHighlight(frame, 0, 0, kSphere, HighlightOptions()); }

// A highlight judged from its measures alone (judgeHighlight): a found peak at full scale.
// Measures: contrast, spread, saturated, compactness, elongation, body rise, fill, area.
Highlight judged(const HighlightMeasures& measures, bool secondCandidate = false) {
  Highlight h;
  h.flag = HighlightFlag::Ok;
  h.peak = 1;
  h.measures = measures;
  judgeHighlight(h, secondCandidate);
  return h;
}

// sRGB-encoded and quantised to 8 bits, as a JPEG export holds the shot.
Image srgb8(Image im) {
  for (auto& v : im.pixels) {
    const double x = v / 65535.0;
    const double e = x <= 0.0031308 ? 12.92 * x : 1.055 * std::pow(x, 1 / 2.4) - 0.055;
    v = static_cast<std::uint16_t>(std::lround(std::clamp(e, 0.0, 1.0) * 255) * 257);
  }
  return im;
}

// The shots' luminance, linear (as from the DNGs) and 8-bit sRGB (as from the exports).
std::pair<MemoryImageStack, MemoryImageStack> shots(const generator::GeneratorOptions& o) {
  const generator::CaptureTruth t = generator::planCapture(o);
  std::vector<Image> linear, encoded;
  for (int i = 0; i < o.images; ++i) {
    linear.push_back(luminance(generator::renderShot(o, t, i)));
    encoded.push_back(srgb8(linear.back()));
  }
  return {MemoryImageStack(std::move(linear)), MemoryImageStack(std::move(encoded))};
}

}  // namespace

TEST_CASE("a compact saturated highlight on a dark sphere is ok with confidence 1") {
  const Highlight h = detect(goodFrame());
  CHECK(h.flag == HighlightFlag::Ok);
  CHECK(h.confidence == 1);
  CHECK(h.reason.empty());
  CHECK(h.x == Approx(70).margin(0.05));
  CHECK(h.y == Approx(50).margin(0.05));
  CHECK(h.measures.contrast > 0.9);
  CHECK(h.measures.spread < 0.03);
  CHECK(h.measures.compactness > 0.9);
  CHECK(h.measures.fill > 0.9);
  CHECK(h.measures.elongation > 0.9);
  CHECK(h.measures.bodyRise < 0.1);
  CHECK(isUsable(h.flag));
}

TEST_CASE("a flat grey sphere is refused as flat, not taken for a highlight at its centre") {
  // The issue: the whole disc was one component, its centroid the centre: a light at 90 deg.
  const Highlight h = detect(sphereFrame(0.5, [](int x, int, double& v) { v += 0.002 * (x % 3); }));
  CHECK(h.flag == HighlightFlag::Flat);
  CHECK_FALSE(isUsable(h.flag));
  CHECK(h.confidence == 0);
  CHECK_THAT(h.reason, Catch::Contains("no peak"));
  CHECK(std::string(flagName(h.flag)) == "flat");
}

TEST_CASE("a saturated sphere is refused as saturated") {
  const Highlight h = detect(sphereFrame(1.0, [](int, int, double&) {}));
  CHECK(h.flag == HighlightFlag::Saturated);
  CHECK(h.confidence == 0);
  CHECK_THAT(h.reason, Catch::Contains("saturated"));
  // Overexposed: a third of the sphere clipped, the rest bright grey.
  const Highlight o = detect(sphereFrame(0.35, [](int x, int, double& v) {
    if (x > 75) v = 1;
  }));
  CHECK(o.flag == HighlightFlag::Saturated);
}

TEST_CASE("a bright patch over a large part of the sphere is refused as large") {
  const Highlight h = detect(sphereFrame(0.05, [](int x, int y, double& v) {
    const double d = std::hypot(x - 65, y - 55);
    if (d < 14) v = 0.9 - 0.01 * d;  // 0.77..0.9 over about 16 % of the measured disc
  }));
  CHECK(h.flag == HighlightFlag::Large);
  CHECK(h.confidence == 0);
  CHECK_THAT(h.reason, Catch::Contains("by at least half"));
}

TEST_CASE("a ring, a streak, a speck or a hot pixel is refused as not compact") {
  // A ring or crescent as the core: judged by its fill (a filled ellipse has 1).
  const Highlight ring = judged({0.9, 0.01, 0, 1, 1, 0, 0.3, 40});
  CHECK(ring.flag == HighlightFlag::NotCompact);
  CHECK_THAT(ring.reason, Catch::Contains("ring"));

  const Highlight streak = detect(sphereFrame(0.03, [](int x, int y, double& v) {
    if (y == 60 && x > 35 && x < 85) v = 1;
  }));
  CHECK(streak.flag == HighlightFlag::NotCompact);
  CHECK(streak.measures.elongation < HighlightLimits::kMinElongation);
  CHECK_THAT(streak.reason, Catch::Contains("streak"));

  // Texture or noise: many equal one-pixel specks; and a single hot pixel in a flat frame (it
  // was taken for a highlight with confidence 1, 62 degrees off).
  const Highlight specks = detect(sphereFrame(0.03, [](int x, int y, double& v) {
    if (x % 9 == 0 && y % 9 == 0) v = 0.9;
  }));
  CHECK(specks.flag == HighlightFlag::NotCompact);
  CHECK(specks.measures.compactness < HighlightLimits::kMinCompactness);
  CHECK_THAT(specks.reason, Catch::Contains("speck"));
  const Highlight hot = detect(sphereFrame(0.03, [](int x, int y, double& v) {
    if (x == 80 && y == 45) v = 1;
  }));
  CHECK(hot.flag == HighlightFlag::NotCompact);
  CHECK(hot.confidence == 0);
}

TEST_CASE("a glare streak through a saturated core: the core's centre, not the streak's") {
  // A core of radius 4 px at (52, 66) with a long saturated streak to its upper right.
  const Highlight h = detect(sphereFrame(0.03, [](int x, int y, double& v) {
    if (std::hypot(x - 52, y - 66) <= 4) v = 1;
    for (int t = 0; t < 30; ++t)
      if (x == 52 + t && y == 66 - t) v = 1;
  }));
  CHECK(isUsable(h.flag));
  CHECK(h.x == Approx(52).margin(0.6));
  CHECK(h.y == Approx(66).margin(0.6));
}

TEST_CASE("with the stack's median, a reflection in every frame is not the highlight") {
  // A bright fixed reflection (a window) at (40, 45) in every frame; the light's highlight at
  // (72, 58) in this one only.
  const auto frame = [](double hx, double hy) {
    return sphereFrame(0.03, [&](int x, int y, double& v) {
      if (std::hypot(x - 40, y - 45) <= 5) v = 1;
      const double d = std::hypot(x - hx, y - hy);
      v += 0.8 * std::exp(-d * d / (2 * 2.0 * 2.0));
    });
  };
  const Image median = frame(-100, -100);  // the frames' median: the reflection alone
  const Highlight without = detect(frame(72, 58));
  CHECK(std::hypot(without.x - 72, without.y - 58) > 5);  // the reflection, brighter, wins alone
  const Highlight with = detectHighlight(frame(72, 58), &median, 0, 0, kSphere, HighlightOptions());
  CHECK(isUsable(with.flag));
  CHECK(with.x == Approx(72).margin(0.1));
  CHECK(with.y == Approx(58).margin(0.1));
}

TEST_CASE("a matte round object, whose whole disc follows the light, is refused as shaded") {
  // Lambertian shading of a sphere lit from the upper left, above its median (lit from the front).
  const auto shaded = [](double lx, double ly) {
    return sphereFrame(0.0, [&](int x, int y, double& v) {
      const double nx = (x - 60) / 45.0, ny = -(y - 60) / 45.0, nz2 = 1 - nx * nx - ny * ny;
      if (nz2 <= 0) return;
      const double lz = std::sqrt(1 - lx * lx - ly * ly);
      v = 0.9 * std::max(0.0, nx * lx + ny * ly + std::sqrt(nz2) * lz);
    });
  };
  const Image median = shaded(0.5, -0.5);
  const Highlight h = detectHighlight(shaded(-0.5, 0.5), &median, 0, 0, kSphere, HighlightOptions());
  CHECK_FALSE(isUsable(h.flag));  // its bright half is also large: refused as large first
  CHECK(h.measures.bodyRise > HighlightLimits::kMaxBodyRise);
  // A body rising under a compact peak (a glossy matte object): refused as shaded.
  const Highlight glossy = judged({0.9, 0.05, 0, 1, 1, 0.4, 1, 40});
  CHECK(glossy.flag == HighlightFlag::Shaded);
  CHECK(std::string(flagName(glossy.flag)) == "shaded");
  CHECK_THAT(glossy.reason, Catch::Contains("matte"));
}

TEST_CASE("a dark sphere has no highlight: flag none, confidence 0, a reason") {
  const Highlight h = detect(sphereFrame(0.01, [](int, int, double&) {}));
  CHECK(h.flag == HighlightFlag::None);
  CHECK(h.confidence == 0);
  CHECK_THAT(h.reason, Catch::Contains("nothing on the sphere is brighter"));
}

TEST_CASE("confidence is the lowest score, each falling linearly to 0 at its limit") {
  Highlight h;
  h.flag = HighlightFlag::Ok;
  h.peak = 1;
  // contrast, spread, saturated, compactness, elongation, body rise, fill, area
  h.measures = {0.9, 0.01, 0, 1, 1, 0, 1, 40};
  judgeHighlight(h, false);
  CHECK(h.confidence == 1);
  h.measures.contrast = 0.675;  // halfway between 0.55 (limit) and 0.80 (score 1)
  judgeHighlight(h, false);
  CHECK(h.flag == HighlightFlag::Ok);
  CHECK(h.confidence == Approx(0.5));
  h.measures.spread = 0.08;  // 2/7 of the way from 0.10 (limit) to 0.03
  judgeHighlight(h, false);
  CHECK(h.confidence == Approx(2.0 / 7));
  h.measures = {0.9, 0.01, 0, 1, 1, 0, 1, 40};
  judgeHighlight(h, true);  // a second candidate nearly as bright
  CHECK(h.flag == HighlightFlag::Multiple);
  CHECK(h.confidence == HighlightLimits::kMultipleCap);
  h.flag = HighlightFlag::Ok;
  h.measures.contrast = 0.54;  // past the limit: refused
  judgeHighlight(h, false);
  CHECK(h.flag == HighlightFlag::Flat);
  CHECK(h.confidence == 0);
}

TEST_CASE("generated captures: every highlight confident, with a margin to every limit") {
  // The e2e small capture (400x300, r 45, seed 7), the detection tests' frames (480x360, r 60,
  // two spheres on strong texture) and a small sphere (r 22); linear (DNG) and 8-bit sRGB
  // (JPEG exports). The benchmark and demo captures (1200x800 r 80, r 30, 1600x1200 r 150,
  // heavy noise, 60 images) measured the same: C >= 0.867, S <= 0.014, H = 1, F >= 0.92,
  // E >= 0.77.
  struct Case {
    int images, width, height, spheres;
    double radius;
    bool strong;
    std::uint64_t seed;
  };
  for (const Case& c : {Case{8, 400, 300, 1, 45, false, 7}, Case{12, 480, 360, 2, 60, true, 5},
                        Case{8, 300, 200, 1, 22, false, 3}}) {
    generator::GeneratorOptions o;
    o.images = c.images;
    o.width = c.width;
    o.height = c.height;
    o.spheres = c.spheres;
    o.sphereRadius = c.radius;
    o.strongTexture = c.strong;
    o.seed = c.seed;
    const auto [linear, encoded] = shots(o);
    for (const bool encode : {false, true}) {
      const MemoryImageStack& stack = encode ? encoded : linear;
      const SphereDetectionOptions detection;
      const StackMedian median(stack, detection.coarseWidth, 2);
      const auto spheres = detectSpheres(median, detection);
      REQUIRE(static_cast<int>(spheres.size()) == c.spheres);
      for (const auto& row : detectHighlights(stack, spheres, HighlightOptions(), 2, &median))
        for (const Highlight& h : row) {
          INFO(c.width << "x" << c.height << " r " << c.radius << (encode ? " sRGB" : " linear") << ": C "
                       << h.measures.contrast << " S " << h.measures.spread << " K " << h.measures.compactness
                       << " F " << h.measures.fill << " E " << h.measures.elongation << " R "
                       << h.measures.bodyRise);
          CHECK(h.flag == HighlightFlag::Ok);
          CHECK(h.confidence == 1);
          CHECK(h.measures.contrast > 0.8);
          CHECK(h.measures.spread < 0.02);
          CHECK(h.measures.compactness > 0.7);
          CHECK(h.measures.fill > 0.75);
          CHECK(h.measures.elongation > 0.7);
          CHECK(h.measures.bodyRise <= HighlightLimits::kGoodBodyRise);
        }
    }
  }
}

TEST_CASE("a circle on the textured relief instead of the sphere: most of its highlights refused") {
  // What a circle given by hand in the wrong place sees. Measured on 320 random circles (radius
  // 20-70, two seeds, normal and strong texture, linear and sRGB): at least 62 % of the
  // highlights refused on every one, so the sphere is refused. Here three, on the e2e capture.
  generator::GeneratorOptions o;
  o.images = 8;
  o.width = 400;
  o.height = 300;
  o.sphereRadius = 45;
  o.seed = 7;
  const auto [linear, encoded] = shots(o);
  for (const bool encode : {false, true}) {
    const MemoryImageStack& stack = encode ? encoded : linear;
    for (const DetectedSphere& wrong : {DetectedSphere{60, 240, 40, 1}, DetectedSphere{200, 150, 45, 1},
                                        DetectedSphere{100, 100, 60, 1}}) {
      int refused = 0;
      const StackMedian median(stack, 800, 2);
      for (const auto& row : detectHighlights(stack, {wrong}, HighlightOptions(), 2, &median))
        refused += !isUsable(row[0].flag);
      INFO("circle " << wrong.cx << "," << wrong.cy << "," << wrong.r << (encode ? " sRGB" : " linear"));
      CHECK(refused >= 6);
    }
  }
}
