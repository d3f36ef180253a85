// Metadata of real camera files. The expected values are what the exiv2 program (0.27.6)
// prints for each file: ground truth from Exiv2 itself, obtained with
//
//   exiv2 -pa tests/data/<folder>/<file>        (interpreted values, e.g. "1/125 s", "F2.9")
//   exiv2 -pv tests/data/<folder>/<file>        (raw rationals, where a value is not exact)
//
// Maker-note values (serials, lenses, ISO of older cameras) are Exiv2's decoding of the
// camera maker's private tags, printed as exiv2 -pa prints them.
#include <catch2/catch.hpp>

#include <filesystem>

#include "core/atomic_file.h"
#include "meta/metadata.h"

using namespace surrogate;
namespace fs = std::filesystem;

namespace {
fs::path fixture(const std::string& name) { return fs::path(SURROGATE_SOURCE_DIR) / "tests/data" / name; }

bool startsAsXmp(const std::string& packet) {
  return packet.rfind("<?xpacket", 0) == 0 || packet.rfind("<x:xmpmeta", 0) == 0;
}
}  // namespace

TEST_CASE("Canon EOS R6 CR3 (read through Exiv2's BMFF support)") {
  const meta::CameraMetadata m = meta::readMetadata(fixture("raw-metadata/Canon-R6-pruned.CR3"));
  CHECK(m.make == "Canon");
  CHECK(m.model == "Canon EOS R6");
  CHECK(m.bodySerial == "093022004357");              // Exif.Photo.BodySerialNumber
  CHECK(m.lens == "RF70-200mm F2.8 L IS USM");        // Exif.Photo.LensModel
  CHECK(m.focalLengthMm == Approx(200.0));            // 200.0 mm
  CHECK(m.fNumber == Approx(25.0));                   // F25
  CHECK(m.exposureTime == "1/4 s");
  CHECK(m.exposureSeconds == Approx(0.25));
  CHECK(m.iso == 100);                                // Exif.Photo.ISOSpeedRatings
  CHECK(m.dateTimeOriginal == "2021:05:12 12:21:21");
  CHECK(m.orientation == 1);                          // top, left
  CHECK(m.pixelWidth == 3408);
  CHECK(m.pixelHeight == 2272);
  CHECK(m.focalPlaneXResolution == Approx(3872.61).epsilon(1e-5));
  CHECK(m.focalPlaneYResolution == Approx(3872.61).epsilon(1e-5));
  CHECK(m.focalPlaneResolutionUnit == 2);             // inch
  // exiv2 -pX prints a packet. Exiv2 parses it from the XMP box without keeping the bytes;
  // the stored packet (camera-padded to 64 KiB) is recovered verbatim.
  REQUIRE(startsAsXmp(m.xmpPacket));
  CHECK(m.xmpPacket.size() == 65536);
  CHECK(readFile(fixture("raw-metadata/Canon-R6-pruned.CR3"), "test").find(m.xmpPacket) != std::string::npos);
}

TEST_CASE("Apple iPhone 12 Pro DNG") {
  const meta::CameraMetadata m = meta::readMetadata(fixture("raw-metadata/IMG_1361.dng"));
  CHECK(m.make == "Apple");
  CHECK(m.model == "iPhone 12 Pro");
  CHECK_FALSE(m.bodySerial);
  CHECK(m.lens == "iPhone 12 Pro back triple camera 4.2mm f/1.6");
  CHECK(m.focalLengthMm == Approx(4.2));
  CHECK(m.fNumber == Approx(1.6));
  CHECK(m.exposureTime == "1/5556 s");
  CHECK(m.exposureSeconds == Approx(1.0 / 5556));
  CHECK(m.iso == 32);
  CHECK(m.dateTimeOriginal == "2020:12:29 14:24:45");
  CHECK(m.orientation == 6);  // right, top
  CHECK(m.pixelWidth == 4032);
  CHECK(m.pixelHeight == 3024);
  CHECK(m.xmpPacket.empty());
}

TEST_CASE("Nikon D70 JPEG: serial, lens and ISO from the Nikon maker notes") {
  const meta::CameraMetadata m = meta::readMetadata(fixture("raw-metadata/exiv2-nikon-d70.jpg"));
  CHECK(m.make == "NIKON CORPORATION");
  CHECK(m.model == "NIKON D70");
  CHECK(m.bodySerial == "NO= 100005e5");  // Exif.Nikon3.SerialNO, trailing spaces dropped
  CHECK(m.lens == "Nikon AF-S DX Zoom-Nikkor 18-70mm f/3.5-4.5G IF-ED");  // Exif.NikonLd2.LensIDNumber
  CHECK(m.iso == 200);                    // Exif.Nikon3.ISOSpeed
  CHECK(m.focalLengthMm == Approx(50.0));
  CHECK(m.fNumber == Approx(9.0));
  CHECK(m.exposureTime == "1/250 s");
  CHECK(m.dateTimeOriginal == "2004:03:30 10:43:46");
  CHECK(m.orientation == 6);
  CHECK(m.pixelWidth == 3008);
  CHECK(m.pixelHeight == 2000);
}

TEST_CASE("Canon PowerShot S40 CRW: metadata although LibRaw cannot decode its pixels") {
  const meta::CameraMetadata m = meta::readMetadata(fixture("raw-metadata/exiv2-canon-powershot-s40.crw"));
  CHECK(m.make == "Canon");
  CHECK(m.model == "Canon PowerShot S40");
  CHECK(m.bodySerial == "43b226716");       // Exif.Canon.SerialNumber as exiv2 prints it
  CHECK_FALSE(m.lens);                      // Exif.CanonCs.LensType prints "n/a"
  CHECK(m.focalLengthMm == Approx(7.1));    // Exif.Canon.FocalLength "7.1 mm"
  CHECK(m.fNumber == Approx(730459.0 / 250000));  // exiv2 -pv: 730459/250000 (F2.9)
  CHECK(m.exposureTime == "1/15 s");
  CHECK(m.iso == 100);                      // Exif.CanonSi.ISOSpeed
  CHECK(m.dateTimeOriginal == "2005:04:23 17:54:36");
  CHECK(m.orientation == 1);
  CHECK(m.pixelWidth == 2272);
  CHECK(m.pixelHeight == 1704);
}

TEST_CASE("Canon EOS D30 CRW, the complete raw") {
  const meta::CameraMetadata m = meta::readMetadata(fixture("raw-real/canon-eos-d30.crw"));
  CHECK(m.make == "Canon");
  CHECK(m.model == "Canon EOS D30");
  CHECK(m.bodySerial == "123502474");       // Exif.Canon.SerialNumber
  // Exif.CanonCs.LensType: Exiv2's reading of Canon's lens code (ambiguous codes are guessed;
  // CanonCs.Lens says 16-35 mm), recorded as Exiv2 prints it.
  CHECK(m.lens == "Canon EF 70-200mm f/2.8L IS II USM");
  CHECK(m.focalLengthMm == Approx(31.0));   // Exif.Canon.FocalLength "31.0 mm"
  CHECK(m.fNumber == Approx(2828427.0 / 500000));  // exiv2 -pv: 2828427/500000 (F5.7)
  CHECK(m.exposureTime == "1 s");
  CHECK(m.exposureSeconds == Approx(1.0));
  CHECK(m.iso == 100);                      // Exif.CanonSi.ISOSpeed
  CHECK(m.dateTimeOriginal == "2018:01:01 13:03:32");
  CHECK(m.orientation == 1);
  CHECK(m.pixelWidth == 2160);
  CHECK(m.pixelHeight == 1440);
}

TEST_CASE("Sony JPEG with XMP: the whole packet is kept verbatim") {
  const meta::CameraMetadata m = meta::readMetadata(fixture("raw-metadata/DSC_3079.jpg"));
  CHECK(m.make == "Sony");
  CHECK(m.model == "D5803");
  CHECK(m.exposureTime == "1/32 s");
  CHECK(m.fNumber == Approx(2.0));
  CHECK(m.iso == 64);
  CHECK(m.focalLengthMm == Approx(4.6));
  CHECK(m.dateTimeOriginal == "2018:01:04 11:42:41");
  CHECK_FALSE(m.orientation);               // no orientation tag in this file
  CHECK(m.pixelWidth == 720);               // no EXIF dimensions: the JPEG's own size
  CHECK(m.pixelHeight == 1280);
  REQUIRE(startsAsXmp(m.xmpPacket));
  CHECK(m.xmpPacket.find("PhotographicSensitivity") != std::string::npos);
  // Verbatim: the packet occurs byte for byte in the file.
  CHECK(readFile(fixture("raw-metadata/DSC_3079.jpg"), "test").find(m.xmpPacket) != std::string::npos);
}

TEST_CASE("an XMP sidecar is read verbatim, and its values through readMetadata") {
  const fs::path sidecar = fixture("raw-metadata/StaffPhotographer-Example.xmp");
  const std::string packet = meta::readXmpSidecar(sidecar);
  CHECK(packet == readFile(sidecar, "test"));
  CHECK(startsAsXmp(packet));
  const meta::CameraMetadata m = meta::readMetadata(sidecar);
  CHECK(m.xmpPacket == packet);  // not Exiv2's re-serialisation
  CHECK(m.dateTimeOriginal == "2003:04:03 00:00:00");
  CHECK(m.pixelWidth == 432);
  CHECK(m.pixelHeight == 293);
  CHECK_FALSE(m.make);
}

TEST_CASE("the Exiv2 version is reported") { CHECK(meta::exiv2Version().rfind("0.", 0) == 0); }
