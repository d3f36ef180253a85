// Each way a capture can be unusable gives a non-zero exit and a message naming the file.
#include <catch2/catch.hpp>

#include <fstream>

#include "carrier/carrier.h"
#include "e2e_support.h"

namespace fs = std::filesystem;

namespace {
void truncateFile(const fs::path& p) { fs::resize_file(p, fs::file_size(p) / 2); }

e2e::CommandResult run(const fs::path& capture) {
  return e2e::surrogate("run " + e2e::quote(capture) + " --quiet");
}

// The run failed, named `name`, and left no carrier posing as complete: if one was written,
// it records the failed step.
void requireRefused(const e2e::CommandResult& r, const std::string& name, const fs::path& capture) {
  INFO(r.output);
  CHECK(r.exitCode == 1);
  CHECK_THAT(r.output, Catch::Contains(name));
  const fs::path carrierPath = capture / "assembly-files" / "carrier.xml";
  if (fs::exists(carrierPath)) {
    const surrogate::carrier::Carrier c = surrogate::carrier::loadCarrier(carrierPath);
    REQUIRE_FALSE(c.data.empty());
    CHECK(c.data.back().status == "failed");
  }
}
}  // namespace

TEST_CASE("an empty capture folder is refused") {
  const fs::path capture = e2e::freshDir("empty") / "capture";
  fs::create_directories(capture / "original-captures");
  requireRefused(run(capture), "original-captures", capture);
  const fs::path none = e2e::freshDir("none");
  requireRefused(run(none), "original-captures", none);
}

TEST_CASE("a missing capture folder is refused") {
  const e2e::CommandResult r = e2e::surrogate("run /nonexistent/capture --quiet");
  CHECK(r.exitCode == 1);
  CHECK_THAT(r.output, Catch::Contains("/nonexistent/capture"));
}

TEST_CASE("two files of one shot in the same folder (duplicate stems) are refused") {
  const fs::path capture = e2e::smallCapture(e2e::freshDir("dup"));
  fs::copy_file(capture / "jpeg-exports/IMG_0002.jpg", capture / "original-captures/IMG_0002.jpg");
  requireRefused(run(capture), "IMG_0002", capture);
}

TEST_CASE("a truncated DNG original is refused by name") {
  const fs::path capture = e2e::smallCapture(e2e::freshDir("trunc-dng"));
  truncateFile(capture / "original-captures/IMG_0004.dng");
  requireRefused(run(capture), "IMG_0004.dng", capture);
}

TEST_CASE("a truncated JPEG export is refused by name") {
  const fs::path capture = e2e::smallCapture(e2e::freshDir("trunc-jpg"));
  truncateFile(capture / "jpeg-exports/IMG_0005.jpg");
  requireRefused(run(capture), "IMG_0005.jpg", capture);
}

TEST_CASE("images of different sizes within one set are refused") {
  const fs::path capture = e2e::smallCapture(e2e::freshDir("sizes"));
  const fs::path other = e2e::smallCapture(e2e::freshDir("sizes-other"), 8);
  // A JPEG of another size in place of one export.
  const e2e::CommandResult g = e2e::runShell(std::string(GENERATOR_EXE) + " --out " +
                                             e2e::quote(other.parent_path() / "big") +
                                             " --images 6 --width 440 --height 300 --formats jpeg");
  REQUIRE(g.exitCode == 0);
  fs::copy_file(other.parent_path() / "big/jpeg-exports/IMG_0006.jpg",
                capture / "jpeg-exports/IMG_0006.jpg", fs::copy_options::overwrite_existing);
  requireRefused(run(capture), "IMG_0006.jpg", capture);
}

TEST_CASE("a .lp file naming images that are not in the capture is refused") {
  const fs::path capture = e2e::smallCapture(e2e::freshDir("lp"));
  std::ofstream(capture / "dome.lp") << "2\nIMG_0001.jpg 0 0 1\nIMG_0042.jpg 0.5 0 0.866\n";
  requireRefused(e2e::surrogate("run " + e2e::quote(capture) + " --lp dome.lp --quiet"), "dome.lp", capture);
  CHECK_FALSE(fs::exists(capture / "assembly-files"));  // refused before any processing
}

TEST_CASE("a file that is not an image, named like one, is refused by name") {
  const fs::path capture = e2e::smallCapture(e2e::freshDir("notimage"));
  std::ofstream(capture / "jpeg-exports/IMG_0003.jpg", std::ios::trunc) << "this is not a JPEG";
  requireRefused(run(capture), "IMG_0003.jpg", capture);
}

TEST_CASE("malformed camera files (past Exiv2 security issues) are refused by name without a crash") {
  const fs::path bad = fs::path(SURROGATE_SOURCE_DIR) / "tests/data/bad-inputs";
  REQUIRE(fs::exists(bad));
  for (const auto& entry : fs::directory_iterator(bad)) {
    if (entry.path().extension() == ".md") continue;
    const fs::path capture = e2e::freshDir("bad") / "capture";
    fs::create_directories(capture / "original-captures");
    fs::copy_file(entry.path(), capture / "original-captures" / entry.path().filename());
    const e2e::CommandResult r = run(capture);
    INFO(entry.path().filename().string() << ": " << r.output);
    CHECK(r.exitCode == 1);
    CHECK_THAT(r.output, Catch::Contains(entry.path().filename().string()));
  }
}
