// Finding and reading a ColorChecker Classic in synthetic pictures (tests/colour/synthetic_chart.h):
// the true corners and patch colours are known, so findChart's corners are pinned to within 2 px
// of the drawing and readChart's means to the drawn X-Rite sRGB values, decoded with the
// IEC 61966-2-1 curve (written out here, not taken from the library).
#include <catch2/catch.hpp>

#include <cmath>
#include <opencv2/core/utility.hpp>

#include "colour/chart_detection.h"
#include "core/error.h"
#include "synthetic_chart.h"

namespace surrogate::colour {
namespace {

using test::ChartScene;
using test::drawChart;

double cornerError(const ChartPlace& p, const std::array<Point, 4>& truth) {
  double worst = 0;
  for (int i = 0; i < 4; ++i)
    worst = std::max(worst, std::hypot(p.corners[i][0] - truth[i][0], p.corners[i][1] - truth[i][1]));
  return worst;
}

double iecDecode(int v8) {
  const double e = v8 / 255.0;
  return e <= 0.04045 ? e / 12.92 : std::pow((e + 0.055) / 1.055, 2.4);
}

void requireFound(const ChartScene& s) {
  const test::DrawnChart d = drawChart(s);
  const std::optional<ChartPlace> p = findChart(d.image);
  INFO("angle " << s.angle << " pitch " << s.pitch << " keystone " << s.keystone);
  REQUIRE(p.has_value());
  INFO("corner 0 found " << p->corners[0][0] << "," << p->corners[0][1] << " drawn "
                         << d.corners[0][0] << "," << d.corners[0][1]);
  CHECK(cornerError(*p, d.corners) < 2.0);
  CHECK(p->method == "found");
  CHECK(std::abs(p->patchSide - s.pitch * (1 - s.gapFraction)) < 1.5);
}

}  // namespace

TEST_CASE("findChart finds an upright chart and its orientation", "[colour][chart]") {
  ChartScene s;
  requireFound(s);
  s.angle = 180, s.cx = 420, s.cy = 310, s.seed = 2;
  requireFound(s);
}

TEST_CASE("findChart finds a chart turned a quarter either way with a small tilt", "[colour][chart]") {
  ChartScene s;
  s.angle = 90 + 4, s.pitch = 40, s.seed = 3;
  requireFound(s);
  s.angle = 270 - 6, s.pitch = 56, s.seed = 4;
  requireFound(s);
}

TEST_CASE("findChart finds a chart seen in mild perspective in 16-bit and linear pictures",
          "[colour][chart]") {
  ChartScene s;
  s.keystone = 0.08, s.angle = 3, s.sixteenBit = true, s.seed = 5;
  requireFound(s);
  s.transfer = Transfer::Linear, s.angle = -5, s.keystone = -0.06, s.pitch = 32, s.seed = 6;
  requireFound(s);
}

TEST_CASE("findChart gives the same place at one thread and at two", "[colour][chart]") {
  ChartScene s;
  s.angle = 8, s.seed = 7;
  const test::DrawnChart d = drawChart(s);
  const int before = cv::getNumThreads();
  cv::setNumThreads(1);
  const std::optional<ChartPlace> one = findChart(d.image);
  cv::setNumThreads(2);
  const std::optional<ChartPlace> two = findChart(d.image);
  cv::setNumThreads(before);
  REQUIRE(one.has_value());
  REQUIRE(two.has_value());
  for (int i = 0; i < 4; ++i) {
    CHECK(one->corners[i][0] == two->corners[i][0]);
    CHECK(one->corners[i][1] == two->corners[i][1]);
  }
}

TEST_CASE("findChart finds nothing in a picture without a chart", "[colour][chart]") {
  CHECK_FALSE(findChart(test::drawNoChart(900, 600, false, 21)).has_value());
  CHECK_FALSE(findChart(test::drawNoChart(900, 600, true, 22)).has_value());
}

TEST_CASE("chartFromCorners refuses corners that make no convex clockwise quadrilateral",
          "[colour][chart]") {
  const std::array<Point, 4> good = {{{100, 80}, {700, 90}, {690, 500}, {95, 490}}};
  CHECK(chartFromCorners(good, "--colour-chart").method == "given");
  const std::array<std::array<Point, 4>, 3> bad = {{
      {{{100, 80}, {95, 490}, {690, 500}, {700, 90}}},   // anticlockwise (mirrored order)
      {{{100, 80}, {700, 90}, {95, 490}, {690, 500}}},   // crossed
      {{{100, 80}, {100, 80}, {690, 500}, {95, 490}}}}};  // two corners at one place
  for (const auto& corners : bad) {
    try {
      chartFromCorners(corners, "--colour-chart");
      FAIL("accepted");
    } catch (const Error& e) {
      CHECK(e.kind() == ErrorKind::Usage);
      CHECK(e.file() == "--colour-chart");
      CHECK(e.message().find("outer corner of dark skin") != std::string::npos);
    }
  }
}

TEST_CASE("patchRegions are the central half of each patch pitch", "[colour][chart]") {
  // A grid 580 x 380 px with a gap of 0.2 of the pitch: pitch 100, patches 80 px, patch 0's
  // centre at (40, 40), patch 23's at (540, 340); the region spans 50 px around it.
  const ChartPlace p = chartFromCorners({{{0, 0}, {580, 0}, {580, 380}, {0, 380}}}, "test");
  CHECK(std::abs(p.patchSide - 80) < 1e-9);
  const auto r = patchRegions(p);
  CHECK(std::abs(r[0].corners[0][0] - 15) < 1e-9);
  CHECK(std::abs(r[0].corners[2][1] - 65) < 1e-9);
  CHECK(std::abs(r[23].corners[0][0] - 515) < 1e-9);
  CHECK(std::abs(r[23].corners[2][1] - 365) < 1e-9);
}

TEST_CASE("readChart means are the drawn colours in linear light", "[colour][chart]") {
  for (const bool sixteen : {false, true}) {
    for (const Transfer t : {Transfer::Srgb, Transfer::Linear}) {
      ChartScene s;
      s.sixteenBit = sixteen, s.transfer = t, s.angle = 12, s.keystone = 0.05;
      const test::DrawnChart d = drawChart(s);
      const ChartReading r = readChart(d.image, chartFromCorners(d.corners, "test"));
      for (int k = 0; k < kChartPatches; ++k)
        for (int c = 0; c < 3; ++c) {
          const double want = iecDecode(test::kDrawnSrgb[k][c]);
          INFO("patch " << k << " channel " << c << " 16-bit " << sixteen);
          CHECK(std::abs(r.patches[k].mean[c] - want) < 0.002 + 0.01 * want);
        }
      CHECK(r.patches[0].pixels > 500);
      CHECK(r.patches[18].clipped == 0);
      CHECK(r.lightGradient < 0.02);
      CHECK(unusableReason(chartFromCorners(d.corners, "test"), r).empty());
    }
  }
}

TEST_CASE("unusableReason names clipping, small patches and uneven light", "[colour][chart]") {
  ChartScene s;
  s.exposure = 1.3;  // white 9.5 at 1.16 of full scale
  test::DrawnChart d = drawChart(s);
  ChartPlace p = chartFromCorners(d.corners, "test");
  ChartReading r = readChart(d.image, p);
  CHECK(r.patches[18].clipped > 0.9);
  CHECK(unusableReason(p, r).find("white 9.5") != std::string::npos);
  CHECK(unusableReason(p, r).find("lower exposure") != std::string::npos);

  s = ChartScene();
  s.lightGradient = 0.3;  // the chart's right edge gets 1.15 / 0.85 of its left's light
  d = drawChart(s);
  p = chartFromCorners(d.corners, "test");
  r = readChart(d.image, p);
  CHECK(std::abs(r.lightGradient - 0.3) < 0.03);
  CHECK(unusableReason(p, r).find("light the chart evenly") != std::string::npos);

  s = ChartScene();
  s.pitch = 12;  // patches 9.6 px
  d = drawChart(s);
  p = chartFromCorners(d.corners, "test");
  CHECK(unusableReason(p, readChart(d.image, p)).find("larger in the frame") != std::string::npos);

  p = chartFromCorners({{{800, 500}, {1400, 500}, {1400, 900}, {800, 900}}}, "test");
  CHECK(unusableReason(p, readChart(d.image, p)).find("outside the image") != std::string::npos);
}

}  // namespace surrogate::colour
