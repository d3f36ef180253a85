#include <catch2/catch.hpp>

#include <cmath>
#include <filesystem>
#include <map>

#include "core/digest.h"
#include "generator/capture_generator.h"
#include "image/decode.h"
#include "meta/metadata.h"

using namespace surrogate;
namespace fs = std::filesystem;

namespace {
generator::GeneratorOptions small() {
  generator::GeneratorOptions o;
  o.images = 4;
  o.width = 320;
  o.height = 240;
  o.sphereRadius = 40;
  o.seed = 11;
  return o;
}

fs::path freshDir(const std::string& name) {
  const fs::path d = fs::temp_directory_path() / ("surrogate-test-generator-" + name);
  fs::remove_all(d);
  return d;
}

std::map<std::string, std::string> hashes(const fs::path& root) {
  std::map<std::string, std::string> out;
  for (const auto& e : fs::recursive_directory_iterator(root))
    if (e.is_regular_file()) out[fs::relative(e.path(), root).string()] = digestFile(e.path()).sha256;
  return out;
}
}  // namespace

TEST_CASE("the same options give byte-identical captures at any thread count") {
  generator::GeneratorOptions a = small(), b = small();
  a.threads = 1;
  b.threads = 2;
  const fs::path da = freshDir("a"), db = freshDir("b");
  generator::writeCapture(a, da);
  generator::writeCapture(b, db);
  const auto ha = hashes(da), hb = hashes(db);
  CHECK(ha.size() == 4 + 4 + 5);  // DNGs, JPEGs, truth files (normals.png among them)
  CHECK(ha == hb);
  fs::remove_all(da);
  fs::remove_all(db);
}

TEST_CASE("a generated DNG decodes through LibRaw to the rendered radiance") {
  const generator::GeneratorOptions o = small();
  const generator::CaptureTruth truth = generator::planCapture(o);
  const fs::path dir = freshDir("dng");
  generator::writeCapture(o, dir);
  const Image rendered = generator::renderShot(o, truth, 1);
  image::DecodeReport report;
  const Image decoded = image::decodeImage(dir / "original-captures/IMG_0002.dng", image::RawDecodeSettings(), &report);
  REQUIRE(decoded.width == o.width);
  REQUIRE(decoded.height == o.height);
  CHECK(report.blackLevel == 512);
  // Demosaicing interpolates two of three channels at every pixel: compare away from the
  // sphere outlines and the strokes by the mean absolute error relative to the mean signal,
  // per channel. AHD on a smooth scene stays within a few percent; a broken mosaic layout,
  // colour matrix or black level would be off by tens of percent.
  for (int c = 0; c < 3; ++c) {
    double err = 0, sum = 0;
    for (int y = 2; y < o.height - 2; ++y)
      for (int x = 2; x < o.width - 2; ++x) {
        err += std::abs(double(decoded.at(x, y, c)) - rendered.at(x, y, c));
        sum += rendered.at(x, y, c);
      }
    INFO("channel " << c);
    CHECK(err / sum < 0.06);
  }
  fs::remove_all(dir);
}

TEST_CASE("Exiv2 reads the generated DNG's camera and exposure") {
  const fs::path dir = freshDir("exif");
  generator::writeCapture(small(), dir);
  const meta::CameraMetadata m = meta::readMetadata(dir / "original-captures/IMG_0001.dng");
  CHECK(m.make == "Surrogate");
  CHECK(m.model == "Synthetic HRTI");
  CHECK(m.iso == 100);
  CHECK(m.fNumber == Approx(8));
  CHECK(m.exposureSeconds == Approx(1.0 / 125).epsilon(0.01));
  CHECK(m.focalLengthMm == Approx(50));
  CHECK(m.bodySerial == "SYN-11");
  fs::remove_all(dir);
}

TEST_CASE("the highlight in a rendered shot is at the mirror point the truth gives") {
  const generator::GeneratorOptions o = small();
  const generator::CaptureTruth truth = generator::planCapture(o);
  for (int i = 0; i < o.images; ++i) {
    const Image im = generator::renderShot(o, truth, i);
    const auto& s = truth.spheres[0];
    const auto& l = truth.lights[i];
    double hx = l[0], hy = l[1], hz = l[2] + 1;
    const double n = std::sqrt(hx * hx + hy * hy + hz * hz);
    const double ex = s.cx + s.r * hx / n, ey = s.cy - s.r * hy / n;
    // Value-weighted centroid of the near-saturated pixels on the sphere.
    double sx = 0, sy = 0, sw = 0;
    for (int y = 0; y < o.height; ++y)
      for (int x = 0; x < o.width; ++x) {
        if (std::hypot(x - s.cx, y - s.cy) > s.r - 1) continue;
        const double v = im.at(x, y, 1);
        if (v < 60000) continue;
        sx += v * x;
        sy += v * y;
        sw += v;
      }
    INFO("shot " << i);
    REQUIRE(sw > 0);
    CHECK(std::hypot(sx / sw - ex, sy / sw - ey) < 0.5);
  }
}

TEST_CASE("the generator's hard cases are deterministic at any thread count, and change the shots they name") {
  generator::GeneratorOptions a = small(), b = small();
  for (generator::GeneratorOptions* o : {&a, &b}) {
    o->reflections = true;
    o->dustSpecks = 5;
    o->glare = 0.5;
    o->darkFrame = 1;
    o->noFlashFrame = 2;
    o->lightConeDeg = 20;
    o->lightConeElevationDeg = 60;
  }
  a.threads = 1;
  b.threads = 2;
  const fs::path da = freshDir("hard-a"), db = freshDir("hard-b");
  generator::writeCapture(a, da);
  generator::writeCapture(b, db);
  CHECK(hashes(da) == hashes(db));
  fs::remove_all(da);
  fs::remove_all(db);
  // Every light within the cone of 20 degrees around elevation 60: elevations from 40 to 80.
  const generator::CaptureTruth t = generator::planCapture(a);
  for (const auto& l : t.lights) {
    const double elevation = std::asin(l[2]) * 180 / M_PI;
    CHECK(elevation >= 40 - 1e-9);
    CHECK(elevation <= 80 + 1e-9);
  }
  // The dark frame at 5 % of the plain shot's signal; the shot without flash far darker still.
  const generator::GeneratorOptions plain = [&] { auto o = a; o.darkFrame = o.noFlashFrame = -1; return o; }();
  double dark = 0, lit = 0, unlit = 0, lit2 = 0;
  const Image d = generator::renderShot(a, t, 1), p = generator::renderShot(plain, t, 1);
  const Image n = generator::renderShot(a, t, 2), p2 = generator::renderShot(plain, t, 2);
  for (std::size_t i = 0; i < d.pixels.size(); ++i) {
    dark += d.pixels[i];
    lit += p.pixels[i];
    unlit += n.pixels[i];
    lit2 += p2.pixels[i];
  }
  CHECK(dark / lit == Approx(generator::kDarkExposure).margin(0.01));
  CHECK(unlit / lit2 < 0.1);
}
