// Metadata of real camera files, checked against what the exiv2 program prints for them
// (`exiv2 -pa FILE`, Exiv2 0.27.6): those values are the ground truth here.
#include <catch2/catch.hpp>

#include <filesystem>

#include "core/error.h"
#include "meta/metadata.h"

using namespace surrogate;
namespace fs = std::filesystem;

namespace {
fs::path fixture(const std::string& name) {
  return fs::path(SURROGATE_SOURCE_DIR) / "tests/data" / name;
}
}  // namespace

TEST_CASE("Canon EOS R6 CR3: camera, serial, lens and exposure as exiv2 prints them") {
  const meta::CameraMetadata m = meta::readMetadata(fixture("raw-metadata/Canon-R6-pruned.CR3"));
  CHECK(m.make == "Canon");
  CHECK(m.model == "Canon EOS R6");
  CHECK(m.bodySerial == "093022004357");
  CHECK(m.lens == "RF70-200mm F2.8 L IS USM");
  CHECK(m.focalLengthMm == Approx(200.0));
  CHECK(m.fNumber == Approx(25.0));
  CHECK(m.exposureTime == "1/4 s");
  CHECK(m.exposureSeconds == Approx(0.25));
  CHECK(m.iso == 100);
  CHECK(m.dateTimeOriginal == "2021:05:12 12:21:21");
  CHECK(m.orientation == 1);
  CHECK(m.pixelWidth == 3408);
}

TEST_CASE("iPhone 12 Pro DNG: lens model, exposure and rotated orientation") {
  const meta::CameraMetadata m = meta::readMetadata(fixture("raw-metadata/IMG_1361.dng"));
  CHECK(m.make == "Apple");
  CHECK(m.model == "iPhone 12 Pro");
  CHECK(m.lens == "iPhone 12 Pro back triple camera 4.2mm f/1.6");
  CHECK(m.exposureTime == "1/5556 s");
  CHECK(m.fNumber == Approx(1.6));
  CHECK(m.iso == 32);
  CHECK(m.focalLengthMm == Approx(4.2));
  CHECK(m.dateTimeOriginal == "2020:12:29 14:24:45");
  CHECK(m.orientation == 6);  // "right, top"
  CHECK(m.pixelWidth == 4032);
}

TEST_CASE("Nikon D70 JPEG") {
  const meta::CameraMetadata m = meta::readMetadata(fixture("raw-metadata/exiv2-nikon-d70.jpg"));
  CHECK(m.make == "NIKON CORPORATION");
  CHECK(m.model == "NIKON D70");
  CHECK(m.exposureTime == "1/250 s");
  CHECK(m.fNumber == Approx(9.0));
  CHECK(m.focalLengthMm == Approx(50.0));
  CHECK(m.dateTimeOriginal == "2004:03:30 10:43:46");
  CHECK(m.orientation == 6);
  CHECK(m.pixelWidth == 3008);
}

TEST_CASE("Canon PowerShot S40 CRW: metadata even though LibRaw cannot decode its pixels") {
  const meta::CameraMetadata m = meta::readMetadata(fixture("raw-metadata/exiv2-canon-powershot-s40.crw"));
  CHECK(m.make == "Canon");
  CHECK(m.model == "Canon PowerShot S40");
  CHECK(m.exposureTime == "1/15 s");
  CHECK(m.fNumber == Approx(730459.0 / 250000));  // exiv2 -pv: 730459/250000 (printed F2.9)
  CHECK(m.dateTimeOriginal == "2005:04:23 17:54:36");
  CHECK(m.pixelWidth == 2272);
}

TEST_CASE("Sony JPEG with XMP: the whole packet is kept verbatim") {
  const meta::CameraMetadata m = meta::readMetadata(fixture("raw-metadata/DSC_3079.jpg"));
  CHECK(m.make == "Sony");
  CHECK(m.model == "D5803");
  CHECK(m.exposureTime == "1/32 s");
  CHECK(m.iso == 64);
  CHECK(m.focalLengthMm == Approx(4.6));
  REQUIRE_FALSE(m.xmpPacket.empty());
  CHECK(m.xmpPacket.find("x:xmpmeta") != std::string::npos);
  CHECK(m.xmpPacket.find("PhotographicSensitivity") != std::string::npos);
}

TEST_CASE("an XMP sidecar is read verbatim") {
  const std::string packet = meta::readXmpSidecar(fixture("raw-metadata/StaffPhotographer-Example.xmp"));
  CHECK(packet.find("x:xmpmeta") != std::string::npos);
}

TEST_CASE("malformed files give an Error naming the file or valid metadata, never a crash") {
  for (const auto& entry : fs::directory_iterator(fixture("bad-inputs"))) {
    if (entry.path().extension() == ".md") continue;
    INFO(entry.path().filename().string());
    try {
      meta::readMetadata(entry.path());
      SUCCEED("read");
    } catch (const Error& e) {
      CHECK(e.file() == entry.path().string());
    }
  }
  CHECK_THROWS_AS(meta::readMetadata("/nonexistent/file.jpg"), Error);
}
