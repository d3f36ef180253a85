// Camera values as photographers write them (meta/camera_text.h), and what the real camera
// files of tests/data record about their lens and time zone.
//
// References: the f-numbers marked on lenses for third stops (f/1.4, 1.6, 1.8, 2, ... 5.6, 6.3,
// 7.1, 8, 9, 10, 11, ...: the ISO 517 / camera-display series), written by hand below; the
// files' values as `exiv2 -pa` and `exiv2 -pv` (0.27.6) print them, quoted beside each check.
#include <catch2/catch.hpp>

#include <filesystem>
#include <fstream>

#include "meta/camera_text.h"
#include "meta/metadata.h"

using namespace surrogate;
namespace fs = std::filesystem;

namespace {
fs::path fixture(const std::string& name) { return fs::path(SURROGATE_SOURCE_DIR) / "tests/data" / name; }
}  // namespace

TEST_CASE("apertures as photographers write them: marked third stops and one decimal below 10") {
  CHECK(meta::apertureText(2828427.0 / 500000) == "f/5.6");  // EOS D30: exiv2 -pv 2828427/500000
  CHECK(meta::apertureText(8) == "f/8");
  CHECK(meta::apertureText(11.3137) == "f/11");              // sqrt(2)^7
  CHECK(meta::apertureText(7.1272) == "f/7.1");              // sqrt(2)^(17/3)
  CHECK(meta::apertureText(6.3496) == "f/6.3");
  CHECK(meta::apertureText(1.6) == "f/1.6");
  CHECK(meta::apertureText(25) == "f/25");
  CHECK(meta::apertureText(2) == "f/2");
  // Not a third stop: one decimal below 10, whole numbers above.
  CHECK(meta::apertureText(730459.0 / 250000) == "f/2.9");   // PowerShot S40: exiv2 prints F2.9
  CHECK(meta::apertureText(4.7568) == "f/4.8");              // a half stop, sqrt(2)^4.5
  CHECK(meta::apertureText(13.4543) == "f/13");              // a half stop, sqrt(2)^7.5
}

TEST_CASE("exposure times and focal lengths and ranges as photographers write them") {
  CHECK(meta::exposureText(1.0 / 125) == "1/125 s");
  CHECK(meta::exposureText(1.0 / 5556) == "1/5556 s");
  CHECK(meta::exposureText(0.25) == "1/4 s");
  CHECK(meta::exposureText(1) == "1 s");
  CHECK(meta::exposureText(2.5) == "2.5 s");
  CHECK(meta::exposureText(0.6) == "0.6 s");
  CHECK(meta::focalLengthText(31) == "31 mm");
  CHECK(meta::focalLengthText(4.2) == "4.2 mm");
  CHECK(meta::focalRangeText(16, 35) == "16-35 mm");
  CHECK(meta::focalRangeText(50, 50) == "50 mm");
}

TEST_CASE("dates in ISO 8601 with the zone when the file records one") {
  CHECK(meta::dateTimeText("2026:01:01 12:00:00", std::nullopt) == "2026-01-01T12:00:00");
  CHECK(meta::dateTimeText("2021:05:12 12:21:21", std::string("+02:00")) == "2021-05-12T12:21:21+02:00");
  CHECK(meta::dateTimeText("2021:05:12 12:21:21", std::string("   ")) == "2021-05-12T12:21:21");
  CHECK(meta::dateTimeText("sometime", std::nullopt) == "sometime");
}

TEST_CASE("the make is not repeated in the model") {
  meta::CameraMetadata m;
  m.make = "Canon";
  m.model = "Canon EOS D30";
  CHECK(meta::cameraText(m) == "Canon EOS D30");
  m.make = "NIKON CORPORATION";
  m.model = "NIKON D70";
  CHECK(meta::cameraText(m) == "NIKON D70");
  m.make = "Sony";
  m.model = "D5803";
  CHECK(meta::cameraText(m) == "Sony D5803");
  m.make = "Apple";
  m.model = "iPhone 12 Pro";
  CHECK(meta::cameraText(m) == "Apple iPhone 12 Pro");
}

TEST_CASE("Canon EOS D30: the reading of the lens code contradicts the recorded 16-35 mm and the range is shown") {
  const meta::CameraMetadata m = meta::readMetadata(fixture("raw-real/canon-eos-d30.crw"));
  CHECK(meta::cameraText(m) == "Canon EOS D30");
  CHECK(m.lensFromMakerNote);                 // Exif.CanonCs.LensType
  CHECK(m.lensMinFocalMm == Approx(16.0));    // exiv2 -pv: Exif.CanonCs.Lens 35 16 1
  CHECK(m.lensMaxFocalMm == Approx(35.0));
  CHECK_FALSE(meta::lensAgreesWithRange(m));
  CHECK(meta::lensText(m) ==
        "16-35 mm (recorded focal range; the lens code reads as Canon EF 70-200mm f/2.8L IS II USM, "
        "which does not match it)");
  CHECK(meta::apertureText(*m.fNumber) == "f/5.6");
  CHECK(meta::focalLengthText(*m.focalLengthMm) == "31 mm");
  CHECK_FALSE(m.offsetTimeOriginal);
}

TEST_CASE("lens names that agree with the recorded range and a range without a name") {
  const meta::CameraMetadata nikon = meta::readMetadata(fixture("raw-metadata/exiv2-nikon-d70.jpg"));
  CHECK(nikon.lensMinFocalMm == Approx(18.0));  // Exif.Nikon3.Lens 18-70mm F3.5-4.5
  CHECK(nikon.lensMaxFocalMm == Approx(70.0));
  CHECK(meta::lensText(nikon) == "Nikon AF-S DX Zoom-Nikkor 18-70mm f/3.5-4.5G IF-ED");

  const meta::CameraMetadata s40 = meta::readMetadata(fixture("raw-metadata/exiv2-canon-powershot-s40.crw"));
  CHECK(meta::lensText(s40) == "7.1-21.3 mm");  // Exif.CanonCs.Lens 7.1 - 21.3 mm; LensType n/a

  const meta::CameraMetadata r6 = meta::readMetadata(fixture("raw-metadata/Canon-R6-pruned.CR3"));
  CHECK_FALSE(r6.lensFromMakerNote);            // Exif.Photo.LensModel names it
  CHECK(r6.lensMinFocalMm == 70.0);             // Exif.Photo.LensSpecification 70/1 200/1 0/1 0/1
  CHECK(r6.lensMaxFocalMm == 200.0);
  CHECK(meta::lensText(r6) == "RF70-200mm F2.8 L IS USM");
  CHECK(r6.offsetTimeOriginal == "+02:00");     // Exif.Photo.OffsetTimeOriginal

  const meta::CameraMetadata sony = meta::readMetadata(fixture("raw-metadata/DSC_3079.jpg"));
  CHECK(meta::lensText(sony).empty());          // no lens field at all: nothing shown
  CHECK_FALSE(sony.bodySerial);
}

TEST_CASE("rationals are read exactly and not through a float") {
  const meta::CameraMetadata m = meta::readMetadata(fixture("raw-metadata/IMG_1361.dng"));
  CHECK(m.focalLengthMm == 4.2);                // exiv2 -pv: 21/5
  CHECK(m.fNumber == 1.6);                      // 8/5
  CHECK(m.offsetTimeOriginal == "-05:00");
  CHECK(m.lensMinFocalMm == 807365.0 / 524263); // LensSpecification 807365/524263 6/1
  CHECK(meta::dateTimeText(*m.dateTimeOriginal, m.offsetTimeOriginal) == "2020-12-29T14:24:45-05:00");
}

TEST_CASE("an XMP sidecar is summarized: software and rating and develop settings and history") {
  const meta::XmpSidecarSummary staff = meta::summarizeXmpSidecar(fixture("raw-metadata/StaffPhotographer-Example.xmp"));
  CHECK(staff.creatorTool == "Adobe Photoshop CS Windows");  // Xmp.xmp.CreatorTool
  CHECK(staff.creator == "John Doe");                        // Xmp.dc.creator
  CHECK(staff.rights == "\xC2\xA9" "2003 Big Newspaper, all rights reserved");
  CHECK(staff.modified == "2007-01-08T13:25:45+01:00");      // Xmp.xmp.MetadataDate
  CHECK_FALSE(staff.rating);
  CHECK(staff.developSettings == 0);
  CHECK(staff.history.empty());

  // A Lightroom-style sidecar written here: what it holds is the reference.
  const fs::path dir = fs::temp_directory_path() / "surrogate-test-sidecar";
  fs::create_directories(dir);
  const fs::path file = dir / "IMG_0001.xmp";
  std::ofstream(file, std::ios::binary)
      << "<x:xmpmeta xmlns:x=\"adobe:ns:meta/\"><rdf:RDF xmlns:rdf=\"http://www.w3.org/1999/02/22-rdf-syntax-ns#\">"
         "<rdf:Description rdf:about=\"\" xmlns:xmp=\"http://ns.adobe.com/xap/1.0/\""
         " xmlns:crs=\"http://ns.adobe.com/camera-raw-settings/1.0/\""
         " xmlns:xmpMM=\"http://ns.adobe.com/xap/1.0/mm/\""
         " xmlns:stEvt=\"http://ns.adobe.com/xap/1.0/sType/ResourceEvent#\""
         " xmp:CreatorTool=\"Adobe Photoshop Lightroom Classic 12.0\" xmp:Rating=\"4\""
         " crs:ProcessVersion=\"11.0\" crs:Exposure2012=\"+0.35\" crs:Contrast2012=\"+10\">"
         "<xmpMM:History><rdf:Seq>"
         "<rdf:li stEvt:action=\"saved\" stEvt:when=\"2026-01-02T10:00:00+01:00\""
         " stEvt:softwareAgent=\"Adobe Photoshop Lightroom Classic 12.0\" stEvt:changed=\"/metadata\"/>"
         "<rdf:li stEvt:action=\"derived\" stEvt:when=\"2026-01-03T11:00:00+01:00\"/>"
         "</rdf:Seq></xmpMM:History></rdf:Description></rdf:RDF></x:xmpmeta>";
  const meta::XmpSidecarSummary lr = meta::summarizeXmpSidecar(file);
  CHECK(lr.creatorTool == "Adobe Photoshop Lightroom Classic 12.0");
  CHECK(lr.rating == "4");
  CHECK(lr.developSettings == 3);
  CHECK(lr.processVersion == "11.0");
  REQUIRE(lr.history.size() == 2);
  CHECK(lr.history[0].action == "saved");
  CHECK(lr.history[0].when == "2026-01-02T10:00:00+01:00");
  CHECK(lr.history[0].software == "Adobe Photoshop Lightroom Classic 12.0");
  CHECK(lr.history[0].changed == "/metadata");
  CHECK(lr.history[1].action == "derived");
  fs::remove_all(dir);
}
