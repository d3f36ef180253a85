// The checks on a capture's lights (hrti/light_checks.h), each on lights whose geometry gives
// the answer in closed form: a light at elevation asin(z), the angle between two directions.
#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

#include "hrti/light_checks.h"

using namespace surrogate::hrti;

namespace {

// Twelve lights on a cone at 45 degrees of elevation, every 30 degrees of azimuth.
LightCheckInput ring() {
  LightCheckInput in;
  for (int i = 0; i < 12; ++i) {
    const double a = i * M_PI / 6, e = M_PI / 4;
    in.lights.push_back({std::cos(e) * std::cos(a), std::cos(e) * std::sin(a), std::sin(e)});
    in.names.push_back("IMG_" + std::to_string(i));
    in.imageMeans.push_back(0.3);
    in.highlightPeaks.push_back(1.0);
  }
  in.spheres = {DetectedSphere{100, 100, 40, 1, 1}};
  in.perSphere.assign(12, {std::nullopt});
  return in;
}

const LightCheck& named(const std::vector<LightCheck>& checks, const std::string& name) {
  for (const LightCheck& c : checks)
    if (c.name == name) return c;
  FAIL("no check " << name);
  return checks.front();
}

}  // namespace

TEST_CASE("lights spread over a cone in front of the object pass every check") {
  const auto checks = checkLights(ring());
  REQUIRE(checks.size() == 5);
  for (const LightCheck& c : checks) {
    INFO(c.name << ": " << c.detail);
    CHECK_FALSE(c.failed);
  }
}

TEST_CASE("a light 5 degrees behind the object's plane fails, one 1 degree behind is within the margin") {
  LightCheckInput in = ring();
  in.lights[3] = {std::cos(-5 * M_PI / 180), 0, std::sin(-5 * M_PI / 180)};
  in.lights[4] = {0, std::cos(-1 * M_PI / 180), std::sin(-1 * M_PI / 180)};
  const auto checks = checkLights(in);
  const LightCheck& c = named(checks, kCheckBelowHorizon);
  CHECK(c.failed);
  CHECK(c.images == std::vector<int>{3});
  CHECK(c.detail.find("IMG_3 (-5 deg)") != std::string::npos);
}

TEST_CASE("lights all within a degree of each other are clustered") {
  LightCheckInput in = ring();
  for (int i = 0; i < 12; ++i) {
    const double a = i * M_PI / 6, t = 0.5 * M_PI / 180;  // 0.5 deg from the axis: pairs at most 1 deg apart
    in.lights[i] = {std::sin(t) * std::cos(a), std::sin(t) * std::sin(a), std::cos(t)};
  }
  const auto checks = checkLights(in);
  CHECK(named(checks, kCheckLightsClustered).failed);
}

TEST_CASE("overlapping circles and spheres that disagree by 40 degrees fail") {
  LightCheckInput in = ring();
  in.spheres = {DetectedSphere{100, 100, 40, 1, 1}, DetectedSphere{150, 100, 40, 1, 1}};  // 50 px apart, r 40 + 40
  const double t = 40 * M_PI / 180;
  for (int i = 0; i < 12; ++i) in.perSphere[i] = {std::array<double, 3>{0, 0, 1}, std::array<double, 3>{std::sin(t), 0, std::cos(t)}};
  const auto checks = checkLights(in);
  CHECK(named(checks, kCheckSpheresOverlap).failed);
  const LightCheck& d = named(checks, kCheckSpheresDisagree);
  CHECK(d.failed);
  CHECK(d.detail.find("40.0 deg") != std::string::npos);
}

TEST_CASE("a frame whose highlight peaks at a tenth of the others', or far darker than its neighbours, is named") {
  LightCheckInput in = ring();
  in.highlightPeaks[5] = 0.1;
  // Linear light: the real light probes' frames range from 0.25 to 2.5 of their neighbours'.
  in.imageMeans[8] = 0.3 * 0.07;  // its neighbours at 30 deg are at 0.3
  in.imageMeans[2] = 0.3 * 0.2;   // 20 %: a raking light may do that, not named
  const auto checks = checkLights(in);
  const LightCheck& c = named(checks, kCheckExposureOutlier);
  CHECK(c.failed);
  CHECK(c.images == std::vector<int>{5, 8});
}

TEST_CASE("a residual far above the others' is an outlier, a spread of residuals is not") {
  CHECK(residualOutliers({9, 10, 11, 12, 13, 14, 15, 16, 17, 18, 19, 97}) == std::vector<int>{11});
  CHECK(residualOutliers({4.4, 3.5, 6.9, 8.3, 12.5, 9.7, 11.6, 9.0, 6.3, 13.2, 8.8, 9.1}).empty());  // a real probe
  CHECK(residualOutliers({1, 1, 50}).empty());  // too few to tell
}

TEST_CASE("a check names every image it fails, not the first six and a count") {
  // 30 images, 8 of which the model misses 25 times as much: each one is to be left out, so
  // each is named ("and 2 more" once left the user to guess which).
  std::vector<double> rmse;
  std::vector<std::string> names;
  for (int i = 0; i < 30; ++i) {
    rmse.push_back(i % 4 == 1 ? 50.0 : 2.0 + 0.01 * i);
    names.push_back("IMG_" + std::to_string(100 + i));
  }
  const LightCheck c = residualCheck(rmse, names);
  INFO(c.detail);
  REQUIRE(c.failed);
  REQUIRE(c.images.size() == 8);
  for (int i : c.images) CHECK(c.detail.find(names[static_cast<std::size_t>(i)] + " (RMSE 50") != std::string::npos);
  CHECK_THAT(c.detail, !Catch::Matches(".*and [0-9]+ more.*"));
}

TEST_CASE("below the horizon by more than its own 95 % bound fails, within it it does not") {
  LightCheckInput in = ring();
  const double e = -3 * M_PI / 180;  // 3 degrees behind the object's plane
  in.lights[4] = {std::cos(e), 0, std::sin(e)};
  in.uncertaintyDeg.assign(12, 1.0);
  CHECK(named(checkLights(in), kCheckBelowHorizon).failed);  // 3 > 1: behind even at the bound
  in.uncertaintyDeg[4] = 4.0;
  CHECK_FALSE(named(checkLights(in), kCheckBelowHorizon).failed);  // the bound reaches the front
  in.uncertaintyDeg[4] = 20.0;  // a bound that large is taken as 5 degrees
  in.lights[4] = {std::cos(-6 * M_PI / 180), 0, std::sin(-6 * M_PI / 180)};
  CHECK(named(checkLights(in), kCheckBelowHorizon).failed);
}

TEST_CASE("a frame whose highlight's halo clips over three times the others' area is too bright") {
  LightCheckInput in = ring();
  in.clippedAreas.assign(12, 400);
  in.clippedAreas[3] = 1200;  // a frame at 300 % exposure: 2.7-4.6 times on the real probes
  in.clippedAreas[7] = 560;   // 1.4 times: within the probes' own range (0.51-1.42)
  const auto checks = checkLights(in);
  const LightCheck& c = named(checks, kCheckExposureOutlier);
  CHECK(c.failed);
  CHECK(c.images == std::vector<int>{3});
  CHECK(c.detail.find("IMG_3 (its highlight's halo is clipped at full scale over 3.0 times the others' area: too "
                      "bright)") != std::string::npos);
  // Highlights that do not clip (most frames at 0) are not compared.
  in.clippedAreas.assign(12, 0);
  in.clippedAreas[3] = 50;
  CHECK_FALSE(named(checkLights(in), kCheckExposureOutlier).failed);
}

TEST_CASE("frame-moved names each frame moved beyond the limit with how far") {
  const std::vector<std::string> names = {"A", "B", "C", "D"};
  const LightCheck c = frameMovedCheck({0.4, 40.3, -1, 7.2}, 7, names);  // C not measured
  CHECK(c.name == "frame-moved");
  CHECK(c.failed);
  CHECK(c.images == std::vector<int>{1, 3});
  CHECK(c.detail.find("B (40 px), D (7 px)") != std::string::npos);
  CHECK_FALSE(frameMovedCheck({0.4, 6.9, -1, 2}, 7, names).failed);
  const auto& all = lightCheckNames();
  CHECK(std::find(all.begin(), all.end(), std::string("frame-moved")) != all.end());
}
