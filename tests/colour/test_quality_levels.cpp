// Guideline levels pinned at their published limits (quality_levels.cpp names the documents):
// FADGI 2023 mean 2.0 / 3.5 / 5.0 / 6.5 and 90th percentile 4 / 7 / 10 / 13 (CIEDE2000);
// Metamorfoze 2.0 Full mean 3 max 7, Light mean 4 max 14 (CIEDE2000 with S_L = 1).
#include <catch2/catch.hpp>

#include "colour/quality_levels.h"

using namespace surrogate::colour;

namespace {

ChartFigures figures(double mean, double p90, double max) {
  ChartFigures f;
  f.mean = mean;
  f.p90 = p90;
  f.max = max;
  f.patches = 24;
  return f;
}

}  // namespace

TEST_CASE("chart figures give mean max and the interpolated 90th percentile") {
  // 1..10: mean 5.5, max 10, 90th percentile at rank 0.9 * 9 = 8.1 -> 9.1.
  const ChartFigures f = chartFigures({3, 1, 2, 10, 4, 5, 6, 7, 8, 9});
  CHECK(f.mean == Approx(5.5).margin(1e-12));
  CHECK(f.max == 10);
  CHECK(f.p90 == Approx(9.1).margin(1e-12));
  CHECK(f.patches == 10);
  CHECK_FALSE(f.unitSL);
  const ChartFigures g = chartFigures({1, 2}, {2, 6});
  CHECK(g.unitSL);
  CHECK(g.meanUnitSL == Approx(4).margin(1e-12));
  CHECK(g.maxUnitSL == 6);
  CHECK(chartFigures({}).patches == 0);
}

TEST_CASE("FADGI 2023 stars at their limits") {
  CHECK(bestLevel(qualityLevels(figures(2.0, 4.0, 9)), "FADGI 2023") == "4 star");
  CHECK(bestLevel(qualityLevels(figures(2.001, 4.0, 9)), "FADGI 2023") == "3 star");
  CHECK(bestLevel(qualityLevels(figures(2.0, 4.001, 9)), "FADGI 2023") == "3 star");
  CHECK(bestLevel(qualityLevels(figures(3.5, 7.0, 9)), "FADGI 2023") == "3 star");
  CHECK(bestLevel(qualityLevels(figures(3.501, 7.0, 9)), "FADGI 2023") == "2 star");
  CHECK(bestLevel(qualityLevels(figures(5.0, 10.0, 20)), "FADGI 2023") == "2 star");
  CHECK(bestLevel(qualityLevels(figures(5.0, 10.001, 20)), "FADGI 2023") == "1 star");
  CHECK(bestLevel(qualityLevels(figures(6.5, 13.0, 20)), "FADGI 2023") == "1 star");
  CHECK(bestLevel(qualityLevels(figures(6.501, 13.0, 20)), "FADGI 2023") == "");
  CHECK(bestLevel(qualityLevels(figures(1.0, 1.0, 1.0)), "FADGI 2023") == "4 star");
}

TEST_CASE("Metamorfoze 2.0 levels at their limits") {
  CHECK(bestLevel(qualityLevels(figures(3.0, 5, 7.0)), "Metamorfoze 2.0") == "Full");
  CHECK(bestLevel(qualityLevels(figures(3.001, 5, 7.0)), "Metamorfoze 2.0") == "Light");
  CHECK(bestLevel(qualityLevels(figures(3.0, 5, 7.001)), "Metamorfoze 2.0") == "Light");
  CHECK(bestLevel(qualityLevels(figures(4.0, 5, 14.0)), "Metamorfoze 2.0") == "Light");
  CHECK(bestLevel(qualityLevels(figures(4.001, 5, 14.0)), "Metamorfoze 2.0") == "");
  CHECK(bestLevel(qualityLevels(figures(4.0, 5, 14.001)), "Metamorfoze 2.0") == "");
  // With the S_L = 1 figures those decide, not the standard ones.
  ChartFigures f = figures(1.0, 2.0, 3.0);
  f.unitSL = true;
  f.meanUnitSL = 3.5;
  f.maxUnitSL = 7.5;
  const std::vector<LevelVerdict> v = qualityLevels(f);
  CHECK(bestLevel(v, "Metamorfoze 2.0") == "Light");
  CHECK(bestLevel(v, "FADGI 2023") == "4 star");
}

TEST_CASE("every level is listed best first with its limits") {
  const std::vector<LevelVerdict> v = qualityLevels(figures(10, 20, 30));
  REQUIRE(v.size() == 6);
  CHECK(v[0].guideline == "FADGI 2023");
  CHECK(v[0].level == "4 star");
  CHECK(v[3].level == "1 star");
  CHECK(v[4].guideline == "Metamorfoze 2.0");
  CHECK(v[4].level == "Full");
  CHECK(v[5].level == "Light");
  for (const LevelVerdict& l : v) CHECK_FALSE(l.met);
  CHECK(v[0].limits.find("mean dE2000 <= 2.0") != std::string::npos);
  CHECK(v[0].limits.find("90th percentile <= 4.0") != std::string::npos);
  CHECK(v[4].limits.find("max <= 7.0") != std::string::npos);
  CHECK(v[4].limits.find("judged here on standard dE2000") != std::string::npos);
  // No patches: nothing is met, however small the (zero) figures.
  CHECK(bestLevel(qualityLevels(ChartFigures{}), "FADGI 2023") == "");
}
