// describeImage on real files of tests/data: the JPEG's size as its SOF0 marker records it
// (height 1280, width 720, read with a few lines of Python from the file's bytes), the CR3's camera as
// `exiv2 -pa` prints it (Exif.Image.Model "Canon EOS R6"); and exposureSettingsText on values
// written here.
#include <catch2/catch.hpp>

#include <filesystem>
#include <fstream>

#include "core/error.h"
#include "meta/camera_text.h"
#include "meta/image_summary.h"

using namespace surrogate;
namespace fs = std::filesystem;

namespace {
fs::path fixture(const std::string& name) { return fs::path(SURROGATE_SOURCE_DIR) / "tests/data" / name; }
}  // namespace

TEST_CASE("describeImage gives a JPEG's size and format and its camera") {
  const meta::ImageSummary s = meta::describeImage(fixture("raw-metadata/DSC_3079.jpg"));
  CHECK(s.decodable);
  CHECK(s.width == 720);
  CHECK(s.height == 1280);
  CHECK(s.format == "JPEG");
  CHECK(s.decodeProblem.empty());
  CHECK(s.camera.has_value());
  CHECK(s.metadataProblem.empty());
}

TEST_CASE("describeImage describes a raw LibRaw does not decode by its metadata, with the refusal") {
  const meta::ImageSummary s = meta::describeImage(fixture("raw-metadata/Canon-R6-pruned.CR3"));
  CHECK_FALSE(s.decodable);
  CHECK(s.width == 0);
  CHECK(s.format.empty());
  CHECK_FALSE(s.decodeProblem.empty());
  REQUIRE(s.camera.has_value());
  CHECK(s.camera->model == "Canon EOS R6");
}

TEST_CASE("describeImage refuses a file that is neither pixels nor metadata") {
  const fs::path dir = fs::temp_directory_path() / "image-summary";
  fs::create_directories(dir);
  std::ofstream(dir / "notes.jpg") << "not an image";
  CHECK_THROWS_AS(meta::describeImage(dir / "notes.jpg"), Error);
  fs::remove_all(dir);
}

TEST_CASE("exposureSettingsText writes the known parts of the exposure in a photographer's order") {
  meta::CameraMetadata m;
  CHECK(meta::exposureSettingsText(m).empty());
  m.iso = 100;
  CHECK(meta::exposureSettingsText(m) == "ISO 100");
  m.focalLengthMm = 31;
  m.fNumber = 5.6;
  m.exposureSeconds = 0.008;
  CHECK(meta::exposureSettingsText(m) == "31 mm, f/5.6, 1/125 s, ISO 100");
  m.exposureSeconds.reset();
  m.exposureTime = "bulb";  // no number: the time as the file writes it
  CHECK(meta::exposureSettingsText(m) == "31 mm, f/5.6, bulb, ISO 100");
}
