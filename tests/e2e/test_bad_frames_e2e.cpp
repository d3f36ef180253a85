// One bad frame among real photographs (issue 52, "No light without its highlight"): each case is
// derived at test time from PSBox's light probes (tests/data/real-rti/SOURCE.md) with OpenCV
// (tests/e2e/bad_frames.h), put in a capture's jpeg-exports/ as PNG, and `surrogate lights` run
// on it with no hints. Each must stop naming the frame and its fault in a photographer's words,
// with the command that leaves it out; the untouched sets must pass without a false alarm.
#include <catch2/catch.hpp>

#include <opencv2/core.hpp>
#include <opencv2/imgcodecs.hpp>

#include <filesystem>
#include <string>

#include "bad_frames.h"
#include "e2e_support.h"
#include "light_errors.h"
#include "real_sets.h"

namespace fs = std::filesystem;

namespace {

using e2e::realData;

// The set's frames and median, read once per test process.
const e2e::ProbeSet& probe(const std::string& set) {
  static const e2e::ProbeSet one = e2e::probeSet(realData("lightprobe-1"));
  static const e2e::ProbeSet two = e2e::probeSet(realData("lightprobe-2"));
  return set == "lightprobe-1" ? one : two;
}

// A capture of the set's twelve JPEGs in which frame `replaced` (0-based) is `bad` as a PNG,
// or, with `extra`, the twelve and `bad` as Image_13.png.
fs::path captureWith(const std::string& set, const std::string& name, int replaced, const cv::Mat& bad,
                     bool extra = false) {
  const e2e::ProbeSet& p = probe(set);
  const fs::path capture = e2e::freshDir(name) / "capture";
  const fs::path exports = capture / "jpeg-exports";
  fs::create_directories(exports);
  for (int i = 0; i < static_cast<int>(p.names.size()); ++i) {
    if (i == replaced && !extra) continue;
    fs::copy_file(realData(set) / (p.names[i] + ".JPG"), exports / (p.names[i] + ".JPG"));
  }
  if (replaced >= 0) REQUIRE(cv::imwrite((exports / ((extra ? "Image_13" : p.names[replaced]) + ".png")).string(), bad));
  return capture;
}

e2e::CommandResult lights(const fs::path& capture, const std::string& more = "") {
  return e2e::surrogate("lights " + e2e::quote(capture) + " -o " + e2e::quote(capture.parent_path() / "lights.lp") +
                        " --quiet" + more);
}

bool says(const e2e::CommandResult& r, const std::string& text) { return r.output.find(text) != std::string::npos; }

}  // namespace

TEST_CASE("the untouched light probes pass with no check failed") {
  for (const std::string set : {"lightprobe-1", "lightprobe-2"}) {
    const fs::path capture = captureWith(set, "clean", -1, cv::Mat());
    const auto r = lights(capture);
    INFO(set << ": " << r.output);
    CHECK(r.exitCode == 0);
    const std::string carrier = e2e::bytesOf(capture / "assembly-files/carrier.xml");
    CHECK(carrier.find("status=\"failed\"") == std::string::npos);
    CHECK(carrier.find("name=\"frame-moved\" status=\"passed\"") != std::string::npos);
    CHECK(carrier.find("flag=\"fixed\"") == std::string::npos);
    CHECK(carrier.find("flag=\"faint\"") == std::string::npos);
  }
}

TEST_CASE("a frame whose highlight is painted out is refused, not given a reflection's light") {
  // Image_05's highlight and its glare's brightest part (a disc of 0.2 of the radius) filled with
  // the frames' median: before, the run took a reflection of the room 72 deg away, flag ok.
  for (const std::string set : {"lightprobe-1", "lightprobe-2"}) {
    const fs::path capture = captureWith(set, "painted", 4, e2e::paintedOut(probe(set), 4, 0.2));
    const auto r = lights(capture);
    INFO(set << ": " << r.output);
    CHECK(r.exitCode == 1);
    CHECK(says(r, "Image_05"));
    CHECK(says(r, "not this image's highlight"));  // lightprobe-1 and -2: the room's reflection (fixed)
    CHECK(says(r, "The light probably missed the sphere or did not fire"));
    CHECK(says(r, "--exclude Image_05 --reason"));
    CHECK_FALSE(says(r, "Image_04"));
    CHECK_FALSE(fs::exists(capture.parent_path() / "lights.lp"));
  }
  // A smaller disc (0.1 r) leaves the glare streak beside it, which rises like a highlight but gives
  // 0.5-0.7 of the others' light: Image_06 of lightprobe-1 was given a light 17.7 deg off.
  const fs::path capture = captureWith("lightprobe-1", "glare", 5, e2e::paintedOut(probe("lightprobe-1"), 5, 0.1));
  const auto r = lights(capture);
  INFO(r.output);
  CHECK(r.exitCode == 1);
  CHECK(says(r, "Image_06.png (faint: "));
  CHECK(says(r, "the highlight is missing"));
}

TEST_CASE("an extra frame where the flash missed the sphere is refused, not put below the horizon") {
  // Image_05 again, its highlight painted out, as a thirteenth frame: before, elevation -1 deg, exit 0.
  const fs::path capture = captureWith("lightprobe-1", "extra", 4, e2e::paintedOut(probe("lightprobe-1"), 4, 0.2), true);
  const auto r = lights(capture);
  INFO(r.output);
  CHECK(r.exitCode == 1);
  CHECK(says(r, "jpeg-exports/Image_13.png"));
  CHECK(says(r, "missed the sphere"));
  CHECK(says(r, "--exclude Image_13 --reason"));
  // Leaving it out is the fix: the twelve give the twelve lights.
  const auto excluded = lights(capture, " --exclude Image_13 --reason \"the flash missed the sphere\"");
  INFO(excluded.output);
  CHECK(excluded.exitCode == 0);
  CHECK(e2e::lpLights(capture.parent_path() / "lights.lp").size() == 12);
}

TEST_CASE("a frame that moved is named as moved, with how far") {
  const e2e::ProbeSet& p = probe("lightprobe-1");
  SECTION("shifted 40 px") {
    const fs::path capture = captureWith("lightprobe-1", "shifted", 4, e2e::shifted(p.frames[4], 40, 0));
    const auto r = lights(capture);
    INFO(r.output);
    CHECK(r.exitCode == 1);
    CHECK(says(r, "frame-moved: the picture moved against the other images"));
    CHECK(says(r, "Image_05 (40 px)"));  // measured 40.3
    CHECK(says(r, "--exclude Image_05 --reason"));
    CHECK_FALSE(says(r, "Image_04"));
    // Accepting it is recorded and lets the run go on.
    const auto accepted = lights(capture, " --accept frame-moved --reason \"a test of the record\"");
    INFO(accepted.output);
    CHECK(accepted.exitCode == 0);
    CHECK(e2e::bytesOf(capture / "assembly-files/carrier.xml").find("name=\"frame-moved\" status=\"accepted\"") !=
          std::string::npos);
  }
  SECTION("turned 3 deg about the frame's centre") {
    const fs::path capture = captureWith("lightprobe-1", "turned", 4, e2e::rotated(p.frames[4], 3));
    const auto r = lights(capture);
    INFO(r.output);
    CHECK(r.exitCode == 1);
    CHECK(says(r, "frame-moved"));
    CHECK(says(r, "Image_05 ("));  // measured 24 px at the quarters' features (7 px limit)
    CHECK_FALSE(says(r, "Image_04"));
  }
}

TEST_CASE("exposure outliers are named both ways: too bright and too dark") {
  const e2e::ProbeSet& p = probe("lightprobe-2");
  SECTION("300 %") {
    const auto r = lights(captureWith("lightprobe-2", "bright", 4, e2e::exposed(p.frames[4], 3)));
    INFO(r.output);
    CHECK(r.exitCode == 1);
    CHECK(says(r, "exposure-outlier"));
    CHECK(says(r, "Image_05 (its highlight's halo is clipped"));  // measured 3.5 times the others' area
    CHECK(says(r, "too bright"));
    CHECK(says(r, "--exclude Image_05 --reason"));
  }
  SECTION("5 %") {
    const auto r = lights(captureWith("lightprobe-2", "dark", 4, e2e::exposed(p.frames[4], 0.05)));
    INFO(r.output);
    CHECK(r.exitCode == 1);
    CHECK(says(r, "exposure-outlier"));
    CHECK(says(r, "Image_05"));
    CHECK(says(r, "too dark"));
  }
}
