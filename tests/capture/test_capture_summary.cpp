// describeCapture on captures the generator writes here: the numbers of shots, their folders
// and size are the generator's options, the format the files' extension.
#include <catch2/catch.hpp>

#include <filesystem>
#include <fstream>

#include "capture/capture_summary.h"
#include "core/error.h"
#include "generator/capture_generator.h"

using namespace surrogate;
namespace fs = std::filesystem;

namespace {

constexpr int kShots = 3, kWidth = 160, kHeight = 120;

// A fresh copy of a generated capture (DNG originals and JPEG exports), without its truth.
fs::path generatedCapture(const std::string& name) {
  static const fs::path source = [] {
    const fs::path dir = fs::temp_directory_path() / "capture-summary-source";
    fs::remove_all(dir);
    generator::GeneratorOptions o;
    o.images = kShots;
    o.width = kWidth;
    o.height = kHeight;
    o.sphereRadius = 25;
    generator::writeCapture(o, dir);
    fs::remove_all(dir / "truth");
    return dir;
  }();
  const fs::path dir = fs::temp_directory_path() / name;
  fs::remove_all(dir);
  fs::copy(source, dir, fs::copy_options::recursive);
  return dir;
}

}  // namespace

TEST_CASE("describeCapture counts the shots, their folders and size, and the .lp left unused") {
  const fs::path capture = generatedCapture("capture-summary-both");
  std::ofstream(capture / "spare.lp") << "1\nIMG_0001.jpg 0 0 1\n";
  const capture::CaptureSummary s = capture::describeCapture(capture);
  CHECK(s.shots == kShots);
  CHECK(s.originals == kShots);
  CHECK(s.exports == kShots);
  CHECK(s.originalsDir == "original-captures");
  CHECK(s.hasOriginals());
  CHECK(s.originalsFolder == "original-captures/");
  CHECK(s.width == kWidth);
  CHECK(s.height == kHeight);
  CHECK(s.format == "DNG");
  CHECK_FALSE(s.lp);
  CHECK(s.unusedLp == std::vector<std::string>{"spare.lp"});
  CHECK_FALSE(s.processed);
}

TEST_CASE("describeCapture of exports alone calls the exports the originals") {
  const fs::path capture = generatedCapture("capture-summary-exports");
  fs::remove_all(capture / "original-captures");
  const capture::CaptureSummary s = capture::describeCapture(capture);
  CHECK(s.shots == kShots);
  CHECK(s.originals == 0);
  CHECK(s.exports == kShots);
  CHECK_FALSE(s.hasOriginals());
  CHECK(s.originalsFolder == "jpeg-exports/");
  CHECK(s.width == kWidth);
  CHECK(s.height == kHeight);
  CHECK(s.format == "JPEG");
  CHECK(s.unusedLp.empty());
}

TEST_CASE("describeCapture refuses a folder that is not a capture") {
  const fs::path empty = fs::temp_directory_path() / "capture-summary-empty";
  fs::create_directories(empty);
  CHECK_THROWS_AS(capture::describeCapture(empty), Error);
}
