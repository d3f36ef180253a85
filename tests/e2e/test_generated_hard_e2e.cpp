// The light front end and the fit on the generator's hard captures (samples/generator:
// --dark-frame, --no-flash-frame, --light-cone), run as a user runs them. The lights are
// compared with the generator's truth (angle between directions, median / max over the
// images); docs/hrti-math.md, "Generated hard cases", has the table.
#include <catch2/catch.hpp>

#include <algorithm>
#include <array>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include "e2e_support.h"
#include "light_errors.h"

namespace fs = std::filesystem;
using e2e::Direction;
using e2e::lpLights;

namespace {

// The scene of tests/hrti/test_detection.cpp (480x360, a sphere of radius 60, 12 shots, seed
// 5) as JPEG exports, with `hard` options; the truth is moved beside the capture.
fs::path generated(const std::string& name, const std::string& hard) {
  return e2e::generatedWithTruth(name, "--images 12 --width 480 --height 360 --sphere-radius 60 --seed 5 --formats jpeg " + hard);
}

// The lights against the truth's, the truth's shot `skipped` (0-based) left out.
e2e::LightErrors compare(const std::vector<Direction>& got, std::vector<Direction> truth, int skipped = -1) {
  if (skipped >= 0) truth.erase(truth.begin() + skipped);
  return e2e::lightErrors(got, truth);
}

std::size_t count(const std::string& text, const std::string& what) {
  std::size_t n = 0;
  for (auto at = text.find(what); at != std::string::npos; at = text.find(what, at + 1)) ++n;
  return n;
}

}  // namespace

TEST_CASE("a frame without flash has no highlight: the lights stop, naming the --exclude command") {
  const fs::path capture = generated("no-flash", "--no-flash-frame 7");
  const fs::path lp = capture.parent_path() / "lights.lp";
  const auto r = e2e::surrogate("lights " + e2e::quote(capture) + " -o " + e2e::quote(lp) + " --quiet");
  INFO(r.output);
  CHECK(r.exitCode == 1);
  CHECK(r.output.find("IMG_0007.jpg (none:") != std::string::npos);
  CHECK(r.output.find("--exclude IMG_0007 --reason") != std::string::npos);
  CHECK(count(r.output, "IMG_00") == count(r.output, "IMG_0007"));  // only that frame is named
  CHECK_FALSE(fs::exists(lp));

  const auto excluded = e2e::surrogate("lights " + e2e::quote(capture) + " -o " + e2e::quote(lp) +
                                       " --quiet --exclude IMG_0007 --reason \"the flash did not fire\"");
  INFO(excluded.output);
  REQUIRE(excluded.exitCode == 0);
  const e2e::LightErrors e = compare(lpLights(lp), lpLights(capture.parent_path() / "truth/lights.lp"), 6);
  INFO("median " << e.median << " max " << e.max);
  CHECK(e.median <= 0.4);  // measured 0.22 / 0.30 deg (the plain capture's exports: 0.18 / 0.29)
  CHECK(e.max <= 0.8);
}

// A frame 4.3 stops under the others: in sRGB its highlight peaks at 52 % of theirs and its
// mean at about 30 % of its neighbours', inside the limits; exposure-outlier compares linear
// light (24 % and 5 %), which names it (LightDirections 5; docs/hrti-math.md).
TEST_CASE("a dark frame (5 % exposure) is named by exposure-outlier before the lights are used") {
  const fs::path capture = generated("dark", "--dark-frame 5");
  const fs::path lp = capture.parent_path() / "lights.lp";
  const auto r = e2e::surrogate("lights " + e2e::quote(capture) + " -o " + e2e::quote(lp) + " --quiet");
  INFO(r.output);
  CHECK(r.exitCode == 1);
  CHECK(r.output.find("exposure-outlier") != std::string::npos);
  CHECK(r.output.find("--exclude IMG_0005 --reason") != std::string::npos);
}

TEST_CASE("a dark frame (5 % exposure) left out with --exclude: the other lights within 0.4 / 0.8 deg") {
  const fs::path capture = generated("dark-excluded", "--dark-frame 5");
  const fs::path lp = capture.parent_path() / "lights.lp";
  const auto r = e2e::surrogate("lights " + e2e::quote(capture) + " -o " + e2e::quote(lp) +
                                " --quiet --exclude IMG_0005 --reason \"the flash was weak\"");
  INFO(r.output);
  REQUIRE(r.exitCode == 0);
  const e2e::LightErrors e = compare(lpLights(lp), lpLights(capture.parent_path() / "truth/lights.lp"), 4);
  INFO("median " << e.median << " max " << e.max);
  CHECK(e.median <= 0.4);  // measured 0.20 / 0.28 deg
  CHECK(e.max <= 0.8);
}

TEST_CASE("lights within 25 degrees of the view axis: hsh3 damped on the record, ptm-lrgb not") {
  const fs::path capture = generated("cone", "--light-cone 25");
  // Not --quiet: the warning is printed where the user looks, not only recorded.
  const auto r = e2e::surrogate("run " + e2e::quote(capture) + " --basis ptm-lrgb --basis hsh3 --no-report");
  INFO(r.output);
  REQUIRE(r.exitCode == 0);
  // Measured 0.17 / 0.42 deg. (With the rim in the median, where the sphere's shadows, cast
  // to the same side in every photograph, stayed: the circle 0.9 px off and 0.8 px too large,
  // 1.76 / 2.14 deg.)
  const e2e::LightErrors e = compare(lpLights(capture / "assembly-files/lights.lp"),
                           lpLights(capture.parent_path() / "truth/lights.lp"));
  INFO("median " << e.median << " max " << e.max);
  CHECK(e.median <= 0.4);
  CHECK(e.max <= 0.8);

  const std::string carrier = e2e::bytesOf(capture / "assembly-files/carrier.xml");
  // The lights are 23 degrees apart (median), far from clustered (under 3).
  CHECK(carrier.find("name=\"lights-clustered\" status=\"passed\"") != std::string::npos);
  // HSH order 3 cannot keep its five order-3 terms at these lights (noise gain about 840, limit
  // 16): they are damped toward order 2, recorded once, for hsh3 only; the PTM (gain 4-18 for
  // such cones, docs/hrti-math.md) stays plain least squares and records nothing.
  CHECK(count(carrier, "name=\"dampedTerms\" value=\"4 5 6 7 8\"") == 1);
  CHECK(count(carrier, "name=\"regularisation\"") == 1);
  CHECK(count(carrier, "too narrow a cone for all the terms of hsh3") == 1);
  CHECK(count(carrier, "too narrow a cone for all the terms of ptm-lrgb") == 0);
  CHECK(r.output.find("too narrow a cone for all the terms of hsh3") != std::string::npos);
}

TEST_CASE("lights within 25 degrees of an elevation of 60: the sphere, not the sphere and its shadow") {
  // Every photograph casts the sphere's shadow to the same side; in the median they outlined a
  // circle of radius 97 around sphere and shadow, lights 47 deg off with no check failing.
  // Measured 0.19 / 0.43 deg.
  const fs::path capture = generated("cone-60", "--light-cone 25 --light-cone-elevation 60");
  const fs::path lp = capture.parent_path() / "lights.lp";
  const auto r = e2e::surrogate("lights " + e2e::quote(capture) + " -o " + e2e::quote(lp) + " --quiet");
  INFO(r.output);
  REQUIRE(r.exitCode == 0);
  const e2e::LightErrors e = compare(lpLights(lp), lpLights(capture.parent_path() / "truth/lights.lp"));
  INFO("median " << e.median << " max " << e.max);
  CHECK(e.median <= 0.4);
  CHECK(e.max <= 0.8);
}

TEST_CASE("a sphere near the frame's edge with its shadows beside it is the sphere, not a larger circle") {
  // The end-to-end tests' own capture (e2e::smallCapture: 400x300, a sphere of radius 45 whose
  // top is 12 px from the edge, DNG originals). Its rim's confidence counted the fit's own
  // inliers, whose limit grows with the points' spread: a circle of radius 59 through the
  // texture and shadows around the sphere scored 0.91, the sphere 0.89, and the lights were
  // 29 / 45 deg off with exit 0. Measured now: 0.39 / 0.60 deg.
  const fs::path capture =
      e2e::generatedWithTruth("edge-sphere", "--images 8 --width 400 --height 300 --sphere-radius 45 --seed 7");
  const fs::path lp = capture.parent_path() / "lights.lp";
  const auto r = e2e::surrogate("lights " + e2e::quote(capture) + " -o " + e2e::quote(lp) + " --quiet");
  INFO(r.output);
  REQUIRE(r.exitCode == 0);
  const e2e::LightErrors e = compare(lpLights(lp), lpLights(capture.parent_path() / "truth/lights.lp"));
  INFO("median " << e.median << " max " << e.max);
  CHECK(e.median <= 0.6);
  CHECK(e.max <= 1.0);
}
