// The generator's colour chart, colour cast and exposure (issue 54): the truth file's patches
// show the reference colours under the closed-form Lambert factor, and a capture made without
// the options keeps the bytes it had before they existed.
#include <catch2/catch.hpp>

#include <array>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "colour/chart_reference.h"
#include "core/digest.h"
#include "core/error.h"
#include "generator/capture_generator.h"

using namespace surrogate;
namespace fs = std::filesystem;

namespace {

generator::GeneratorOptions chartOptions() {
  generator::GeneratorOptions o;
  o.images = 3;
  o.width = 400;
  o.height = 300;
  o.sphereRadius = 40;
  o.seed = 5;
  o.noise = 0;          // the closed form below holds before noise
  o.shadows = false;    // and where nothing shades the chart
  o.colourChart = true;
  o.formats = generator::OutputFormats::Jpeg;
  return o;
}

struct Patch {
  double x, y, side, L, a, b, r, g, bl;
};

struct ChartFile {
  std::string reference;
  std::array<double, 8> corners{};
  std::vector<Patch> patches;
};

ChartFile readChartFile(const fs::path& path) {
  std::ifstream in(path);
  ChartFile f;
  std::string line;
  while (std::getline(in, line)) {
    std::istringstream s(line);
    std::string key;
    s >> key;
    if (key == "reference") s >> f.reference;
    if (key == "corners")
      for (double& c : f.corners) s >> c;
    if (key == "patch") {
      int k;
      Patch p;
      s >> k >> p.x >> p.y >> p.side >> p.L >> p.a >> p.b >> p.r >> p.g >> p.bl;
      REQUIRE(k == static_cast<int>(f.patches.size()));
      f.patches.push_back(p);
    }
  }
  return f;
}

std::string sha256(const Image& im) {
  MultiDigest d({DigestAlgorithm::Sha256});
  d.update(im.pixels.data(), im.pixels.size() * sizeof(im.pixels[0]));
  return d.hex(DigestAlgorithm::Sha256);
}

}  // namespace

TEST_CASE("the chart truth patch centres show the reference colours under the Lambert factor, cast and exposure") {
  struct Case { const char* cast; double exposure; };
  for (const Case& c : {Case{"none", 1.0}, Case{"warm", 1.25}}) {
    generator::GeneratorOptions o = chartOptions();
    o.colourCast = generator::parseColourCast(c.cast);
    o.exposure = c.exposure;
    const fs::path dir = fs::temp_directory_path() / (std::string("surrogate-test-chart-") + c.cast);
    fs::remove_all(dir);
    generator::writeCapture(o, dir);
    const ChartFile f = readChartFile(dir / "truth/colour-chart.txt");
    REQUIRE(f.patches.size() == 24);
    CHECK(f.reference == "colorchecker-classic-2014");
    // X-Rite's published values for charts made after November 2014: dark skin, white 9.5.
    CHECK(f.patches[0].L == Approx(37.54).margin(0.005));
    CHECK(f.patches[0].a == Approx(14.37).margin(0.005));
    CHECK(f.patches[18].L == Approx(95.19).margin(0.005));
    // 400 px wide: patches of 0.04 x 400 = 16 px, 0.2 of that between them; the grid's top side
    // runs from patch 0's outer corner to patch 5's, 6 sides and 5 gaps long.
    CHECK(f.patches[0].side == Approx(16));
    CHECK(std::hypot(f.corners[2] - f.corners[0], f.corners[3] - f.corners[1]) == Approx(6 * 16 + 5 * 3.2));
    CHECK(std::hypot(f.corners[6] - f.corners[0], f.corners[7] - f.corners[1]) == Approx(4 * 16 + 3 * 3.2));
    CHECK(f.corners[1] > 150);  // in the bottom half of the frame, clear of the sphere (top right)
    const generator::CaptureTruth truth = generator::planCapture(o);
    const auto& m = o.colourCast;
    for (int i = 0; i < o.images; ++i) {
      const Image shot = generator::renderShot(o, truth, i);
      // Flat and level: the normal is (0, 0, 1), so the light's z is the cosine (distant light).
      const double e = (0.85 * truth.lights[i][2] + 0.03) * 0.8 * c.exposure * 65535;
      for (int k = 0; k < 24; ++k) {
        const Patch& p = f.patches[k];
        const std::array<double, 3> albedo = {std::max(0.0, p.r), std::max(0.0, p.g), std::max(0.0, p.bl)};
        for (int ch = 0; ch < 3; ++ch) {
          const double expected = (m[3 * ch] * albedo[0] + m[3 * ch + 1] * albedo[1] + m[3 * ch + 2] * albedo[2]) * e;
          INFO("cast " << c.cast << " shot " << i << " patch " << k << " channel " << ch);
          CHECK(std::abs(shot.at(static_cast<int>(std::lround(p.x)), static_cast<int>(std::lround(p.y)), ch) - expected) <= 1.0);
        }
      }
    }
    fs::remove_all(dir);
  }
}

TEST_CASE("without the colour options the shots and normals keep the bytes they had before them") {
  generator::GeneratorOptions o;
  o.images = 4;
  o.width = 320;
  o.height = 240;
  o.sphereRadius = 40;
  o.seed = 11;
  // sha256 of the 16-bit samples as rendered before issue 54 (commit 2c7b728).
  generator::CaptureTruth t = generator::planCapture(o);
  CHECK(t.chart.reference.empty());
  CHECK(sha256(generator::renderShot(o, t, 1)) == "dd8575200b0b9275811e55d3fbab41e2630cc4e3996fd5250e4020c2d940bd28");
  CHECK(sha256(generator::trueNormals(o, t)) == "c8f357f59a3b044277f542b8b9843aa4346b75bad6306a9db6a3afd8ab25b1b3");
  o.spheres = 2;
  o.lightDistance = 2;
  o.darkFrame = 2;
  o.colourCast = generator::parseColourCast("1,0,0,0,1,0,0,0,1");  // the identity named in full
  t = generator::planCapture(o);
  CHECK(sha256(generator::renderShot(o, t, 0)) == "ae42abec92e73c26bc75a20286028176b8df82137a7adb11acd5cd122d862962");
  CHECK(sha256(generator::renderShot(o, t, 2)) == "cc8d92314e019a72386ac780948d8a43fdd3d40ae0888485ce733a25c7665300");
}

TEST_CASE("impossible colour options are refused") {
  CHECK(generator::parseColourCast("none") == generator::kNoColourCast);
  CHECK(generator::parseColourCast("warm") != generator::kNoColourCast);
  CHECK(generator::parseColourCast("cool") != generator::kNoColourCast);
  CHECK_THROWS_AS(generator::parseColourCast("tungsten"), Error);
  CHECK_THROWS_AS(generator::parseColourCast("1,0,0,0,1,0,0,0"), Error);
  CHECK_THROWS_AS(generator::parseColourCast("1,0,0,0,1,0,0,0,1,0"), Error);
  CHECK(std::string(colour::kDefaultChartReference) == generator::GeneratorOptions().chartReference);
  generator::GeneratorOptions o = chartOptions();
  o.width = o.height = 100;  // patches of 4 px
  CHECK_THROWS_AS(generator::planCapture(o), Error);
  o = chartOptions();
  o.chartReference = "colorchecker-sg";
  CHECK_THROWS_AS(generator::planCapture(o), Error);
  o = chartOptions();
  o.exposure = 0;
  CHECK_THROWS_AS(generator::planCapture(o), Error);
}
