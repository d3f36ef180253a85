// The light front end on real photographs (tests/data/real-rti/SOURCE.md), as a new user runs it:
// `surrogate lights` with no hints. Each case states its tolerance against the dataset's own
// reference light directions (angle between directions: median / max over the images).
#include <catch2/catch.hpp>

#include <opencv2/core.hpp>
#include <opencv2/imgcodecs.hpp>

#include <algorithm>
#include <array>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include "e2e_support.h"
#include "light_errors.h"
#include "real_sets.h"

namespace fs = std::filesystem;
using e2e::Direction;
using e2e::lpLights;
using e2e::realData;

namespace {

// lights.txt of the CSE 576 sets: the count, then x y z per image, y up.
std::vector<Direction> countedLights(const fs::path& file) {
  std::ifstream in(file);
  int n = 0;
  in >> n;
  std::vector<Direction> out(n);
  for (Direction& d : out) in >> d[0] >> d[1] >> d[2];
  return out;
}

}  // namespace

// `surrogate lights` with no hints on a PSBox light probe set, against its reference lights.
e2e::LightErrors probeErrors(const std::string& set) {
  const fs::path capture = e2e::realCapture(set, set);
  const fs::path lp = capture.parent_path() / "lights.lp";
  const auto r = e2e::surrogate("lights " + e2e::quote(capture) + " -o " + e2e::quote(lp) + " --quiet");
  INFO(r.output);
  REQUIRE(r.exitCode == 0);
  return e2e::lightErrors(lpLights(lp), e2e::psboxLights(set));
}

TEST_CASE("a black sphere filling the frame, the scene reflected in it, is found without hints") {
  const e2e::LightErrors e = probeErrors("lightprobe-1");
  INFO("median " << e.median << " max " << e.max);
  // Measured 0.63 / 1.20 deg (docs/hrti-math.md, "What limits the accuracy"): the clipped
  // highlights' centres are their plateaus' deepest points; the rest is mostly the rim (with the
  // dataset's own circle 0.26 / 0.65).
  CHECK(e.median <= 0.8);
  CHECK(e.max <= 1.6);
}

TEST_CASE("the second PSBox light probe, another sphere and room, is found without hints") {
  const e2e::LightErrors e = probeErrors("lightprobe-2");
  INFO("median " << e.median << " max " << e.max);
  CHECK(e.median <= 0.7);  // measured 0.51 / 0.78 deg (1.08 / 3.41 with the core's centroid)
  CHECK(e.max <= 1.1);
}

TEST_CASE("a chrome ball on black is found, or refused, never confidently wrong") {
  const fs::path capture = e2e::realCapture("chrome", "chrome");
  const fs::path lp = capture.parent_path() / "lights.lp";
  const auto r = e2e::surrogate("lights " + e2e::quote(capture) + " -o " + e2e::quote(lp) + " --quiet");
  INFO(r.output);
  if (r.exitCode != 0) {
    CHECK(r.exitCode == 1);
    CHECK(r.output.find("--sphere-roi") != std::string::npos);
    return;
  }
  const e2e::LightErrors e = e2e::lightErrors(lpLights(lp), countedLights(realData("chrome") / "lights.txt"));
  INFO("median " << e.median << " max " << e.max);
  // Measured 1.87 / 8.33 deg: the reference's highlights lie up to 8 px from ours, nearly all to
  // their left (docs/hrti-math.md, "What limits the accuracy").
  CHECK(e.median <= 2.2);
}

TEST_CASE("photographs without a sphere are refused, saying what to do") {
  const fs::path capture = e2e::realCapture("objects", "objects");
  const auto r = e2e::surrogate("lights " + e2e::quote(capture) + " -o " +
                                e2e::quote(capture.parent_path() / "lights.lp") + " --quiet");
  INFO(r.output);
  CHECK(r.exitCode == 1);
  CHECK(r.output.find("no sphere was found") != std::string::npos);
  CHECK(r.output.find("--sphere-roi X,Y,W,H") != std::string::npos);
  CHECK(r.output.find("--sphere CX,CY,R") != std::string::npos);
  CHECK_FALSE(fs::exists(capture.parent_path() / "lights.lp"));
}

TEST_CASE("a dark frame among good ones is named with the command that leaves it out") {
  const fs::path capture = e2e::realCapture("lightprobe-1", "dark");
  const fs::path shot = capture / "jpeg-exports/Image_05.JPG";
  cv::Mat image = cv::imread(shot.string(), cv::IMREAD_COLOR);
  REQUIRE(!image.empty());
  image.convertTo(image, -1, 0.12, 0);  // 12 % exposure: the highlight is still there
  REQUIRE(cv::imwrite(shot.string(), image));
  const fs::path lp = capture.parent_path() / "lights.lp";
  const auto r = e2e::surrogate("lights " + e2e::quote(capture) + " -o " + e2e::quote(lp) + " --quiet");
  INFO(r.output);
  CHECK(r.exitCode == 1);
  CHECK(r.output.find("exposure-outlier") != std::string::npos);
  CHECK(r.output.find("--exclude Image_05 --reason") != std::string::npos);
  CHECK(r.output.find("Image_04") == std::string::npos);  // only the dark one is named
  CHECK_FALSE(fs::exists(lp));

  // Accepting needs a reason and a known check; leaving the frame out is the fix.
  const auto noReason = e2e::surrogate("lights " + e2e::quote(capture) + " -o " + e2e::quote(lp) +
                                       " --quiet --accept exposure-outlier");
  CHECK(noReason.exitCode == 2);
  const auto unknown = e2e::surrogate("lights " + e2e::quote(capture) + " -o " + e2e::quote(lp) +
                                      " --quiet --accept everything --reason x");
  CHECK(unknown.exitCode == 2);
  CHECK(unknown.output.find("lights-below-horizon") != std::string::npos);
  const auto excluded = e2e::surrogate("lights " + e2e::quote(capture) + " -o " + e2e::quote(lp) +
                                       " --quiet --exclude Image_05 --reason \"flash at 12 %\"");
  INFO(excluded.output);
  CHECK(excluded.exitCode == 0);
  CHECK(lpLights(lp).size() == 11);
}

TEST_CASE("an accepted check is recorded and lets the run go on") {
  const fs::path capture = e2e::realCapture("lightprobe-1", "accepted");
  const fs::path shot = capture / "jpeg-exports/Image_05.JPG";
  cv::Mat image = cv::imread(shot.string(), cv::IMREAD_COLOR);
  image.convertTo(image, -1, 0.12, 0);
  REQUIRE(cv::imwrite(shot.string(), image));
  const fs::path lp = capture.parent_path() / "lights.lp";
  const auto r = e2e::surrogate("lights " + e2e::quote(capture) + " -o " + e2e::quote(lp) +
                                " --quiet --accept exposure-outlier --reason \"a test of the record\"");
  INFO(r.output);
  REQUIRE(r.exitCode == 0);
  const std::string carrier = e2e::bytesOf(capture / "assembly-files/carrier.xml");
  CHECK(carrier.find("name=\"exposure-outlier\" status=\"accepted\"") != std::string::npos);
  CHECK(carrier.find("a test of the record") != std::string::npos);
}

TEST_CASE("a sphere cut by the frame's edge, given by hand, is fitted to its visible rim") {
  // LightProbe-1 cropped to columns 300-1099: the sphere (the dataset's circle 535.9,478.0,421.1)
  // loses 185 px to the left edge, and its radius is more than half the 800x1000 frame's smaller
  // side, which was refused as "a sphere that size cannot be in the images". 84 % of its disc is
  // in the frame.
  const fs::path capture = e2e::freshDir("cut-sphere") / "capture";
  fs::create_directories(capture / "jpeg-exports");
  for (int i = 1; i <= 12; ++i) {
    const std::string name = std::string("Image_") + (i < 10 ? "0" : "") + std::to_string(i);
    const cv::Mat image = cv::imread((realData("lightprobe-1") / (name + ".JPG")).string(), cv::IMREAD_COLOR);
    REQUIRE(image.cols == 1100);
    REQUIRE(cv::imwrite((capture / "jpeg-exports" / (name + ".png")).string(), image(cv::Rect(300, 0, 800, 1000))));
  }
  const fs::path lp = capture.parent_path() / "lights.lp";
  // The dataset's circle moved into the crop, rounded as a person would give it.
  const auto r = e2e::surrogate("lights " + e2e::quote(capture) + " -o " + e2e::quote(lp) +
                                " --quiet --sphere 236,478,421 --reason \"the light probe, cut by the left edge\"");
  INFO(r.output);
  REQUIRE(r.exitCode == 0);
  const e2e::LightErrors e = e2e::lightErrors(lpLights(lp), e2e::psboxLights("lightprobe-1"));
  INFO("median " << e.median << " max " << e.max);
  CHECK(e.median <= 1.0);  // measured 0.79 / 1.30 deg (the whole frame, no hints: 0.63 / 1.20)
  CHECK(e.max <= 1.6);
  const std::string carrier = e2e::bytesOf(capture / "assembly-files/carrier.xml");
  CHECK(carrier.find("84 % of its disc in the frame, fitted to its visible rim") != std::string::npos);

  // Less than half of the disc in the frame is still refused, saying so.
  const auto sliver = e2e::surrogate("lights " + e2e::quote(capture) + " -o " + e2e::quote(lp) +
                                     " --quiet --sphere 10,478,700 --reason \"a typo\"");
  CHECK(sliver.exitCode == 2);
  CHECK(sliver.output.find("needs at least half of its disc inside it") != std::string::npos);
}
