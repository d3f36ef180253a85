// formats::identifyPronom against PRONOM's published signatures (release 118, the entries kept
// in tests/data/pronom/ and matched by pronom_reference.cpp, which shares no code with
// src/formats): on real files of the repository, on files Surrogate writes, and on headers built
// here for each variant rule (mappings/pronom.md).
#include <catch2/catch.hpp>

#include <filesystem>
#include <fstream>

#include "core/image.h"
#include "formats/pronom.h"
#include "formats/ptm.h"
#include "image/write.h"
#include "pronom_reference.h"

namespace fs = std::filesystem;
using namespace surrogate;
using formats::identifyPronom;
using formats::identifyPronomFile;

namespace {

fs::path fixture(const std::string& name) { return fs::path(SURROGATE_SOURCE_DIR) / "tests/data" / name; }

std::string hex(const std::string& h) {
  std::string out;
  for (std::size_t i = 0; i + 1 < h.size(); i += 2) out.push_back(static_cast<char>(std::stoi(h.substr(i, 2), nullptr, 16)));
  return out;
}

// The file's PUID as Surrogate finds it is the one format left when PRONOM's kept signatures
// are matched by the reference: its own signature matches, and every kept format that matches
// too is one it has priority over (none PRONOM prefers to it matches).
void requireAsPronom(const std::string& bytes, const std::string& puid, const std::string& what) {
  INFO(what);
  const formats::PronomIdentity id = identifyPronom(bytes);
  CHECK(id.puid == puid);
  CHECK(pronom_reference::matches(puid, bytes));
  for (const std::string& preferred : pronom_reference::preferredTo(puid)) {
    INFO("preferred to " + puid + ": " + preferred);
    CHECK_FALSE(pronom_reference::matches(preferred, bytes));
  }
  CHECK(pronom_reference::identify(bytes) == std::vector<std::string>{puid});
}

// A JPEG: SOI, the given segments, a little entropy-coded data, EOI.
std::string jpeg(const std::string& segments) { return hex("FFD8") + segments + hex("FFDB0004000001020304FFD9"); }

std::string jfif(int minor) {
  return hex("FFE00010") + "JFIF" + std::string(1, '\0') + hex("01") + std::string(1, static_cast<char>(minor)) +
         hex("01004800480000");
}

// An Exif APP1 first (as cameras write it): IFD0 points to the Exif IFD, which holds
// ExifVersion `version` (four characters).
std::string exif(const std::string& version, bool bigEndian) {
  const std::string tiff =
      bigEndian ? hex("4D4D002A00000008" "0001" "8769000400000001" "0000001A" "00000000" "0001" "9000000700000004") +
                      version + hex("00000000")
                : hex("49492A0008000000" "0100" "6987040001000000" "1A000000" "00000000" "0100" "0090070004000000") +
                      version + hex("00000000");
  const std::string body = "Exif" + std::string(2, '\0') + tiff;
  const std::size_t length = body.size() + 2;
  return hex("FFE1") + std::string(1, static_cast<char>(length >> 8)) + std::string(1, static_cast<char>(length & 0xff)) + body;
}

// A TIFF (little- or big-endian) whose first IFD holds DNGVersion 1.minor.0.0, with `padding`
// bytes between the header and the IFD.
std::string dng(int minor, bool bigEndian, std::size_t padding = 0) {
  const std::uint32_t offset = static_cast<std::uint32_t>(8 + padding);
  std::string out = bigEndian ? hex("4D4D002A") : hex("49492A00");
  for (int k = 0; k < 4; ++k) {
    const int shift = bigEndian ? 24 - 8 * k : 8 * k;
    out.push_back(static_cast<char>((offset >> shift) & 0xff));
  }
  out += std::string(padding, '\x55');
  const char v = static_cast<char>(minor);
  out += bigEndian ? hex("0001C61200010000000401") + std::string(1, v) + hex("0000")
                   : hex("010012C601000400000001") + std::string(1, v) + hex("0000");
  return out + hex("00000000");
}

// A PNG: signature, IHDR, the given chunks (type and data; CRCs are not checked by signatures,
// left zero), one IDAT and IEND.
std::string png(const std::vector<std::string>& chunkTypes) {
  std::string out = hex("89504E470D0A1A0A0000000D49484452000000010000000108000000003A7E9B55");
  for (const std::string& type : chunkTypes) out += hex("00000001") + type + "x" + hex("00000000");
  return out + hex("0000000A49444154789C6300010000050001") + hex("0D0A2DB4") + hex("0000000049454E44AE426082");
}

}  // namespace

TEST_CASE("PRONOM: the built-in signatures are those of the release kept for the tests", "[formats][pronom]") {
  CHECK(formats::pronomRelease() == "118");
  CHECK(pronom_reference::release() == "118");
}

TEST_CASE("PRONOM: real camera files identify as DROID identifies them", "[formats][pronom]") {
  const std::vector<std::pair<std::string, std::string>> files = {
      {"raw-metadata/IMG_1361.dng", "fmt/730"},                 // DNGVersion 1.4
      {"raw-metadata/Canon-R6-pruned.CR3", "fmt/1595"},         // Canon Raw 3
      {"raw-metadata/exiv2-canon-powershot-s40.crw", "fmt/593"}, // Canon RAW 1 (CIFF)
      {"raw-real/canon-eos-d30.crw", "fmt/593"},
      {"raw-metadata/DSC_3079.jpg", "fmt/43"},                  // JFIF 1.01 before its Exif
      {"raw-metadata/exiv2-nikon-d70.jpg", "fmt/43"},
      {"raw-metadata/StaffPhotographer-Example.xmp", "fmt/570"}, // XMP packet
      {"real-rti/objects/Image_01.png", "fmt/11"},              // no iCCP, sPLT, sRGB or iTXt
      {"real-rti/chrome/chrome.00.png", "fmt/11"},
  };
  for (const auto& [name, puid] : files) {
    requireAsPronom(pronom_reference::bytesOf(fixture(name).string()), puid, name);
    CHECK(identifyPronomFile(fixture(name)).puid == puid);
  }
  int jpegs = 0;
  for (const auto& entry : fs::directory_iterator(fixture("real-rti/lightprobe-1")))
    if (entry.path().extension() == ".JPG") {
      requireAsPronom(pronom_reference::bytesOf(entry.path().string()), "fmt/43", entry.path().string());
      ++jpegs;
    }
  CHECK(jpegs == 12);
}

TEST_CASE("PRONOM: a PNG Surrogate writes is PNG 1.2 and a PTM it writes is fmt/519", "[formats][pronom]") {
  const fs::path dir = fs::temp_directory_path() / "surrogate-test-pronom";
  fs::create_directories(dir);
  for (int channels : {1, 3})
    for (int bits : {8, 16}) {
      Image image(64, 48, channels);
      image.bitsPerSample = bits;
      for (std::size_t i = 0; i < image.pixels.size(); ++i) image.pixels[i] = static_cast<std::uint16_t>(i * 2654435761u);
      const fs::path file = dir / ("picture-" + std::to_string(channels) + "-" + std::to_string(bits) + ".png");
      image::writePng(image, file);
      requireAsPronom(pronom_reference::bytesOf(file.string()), "fmt/13", file.string());
      const formats::PronomIdentity id = identifyPronomFile(file);
      CHECK(id.describe() == "Portable Network Graphics 1.2 (fmt/13)");
    }
  formats::PtmFile ptm;
  ptm.width = 3;
  ptm.height = 2;
  ptm.scale = {1, 1, 1, 1, 1, 1};
  ptm.coefficients.assign(ptm.texels() * 6, 7);
  ptm.rgb.assign(ptm.texels() * 3, 9);
  const fs::path file = dir / "model.ptm";
  formats::writePtm(file, ptm);
  requireAsPronom(pronom_reference::bytesOf(file.string()), "fmt/519", file.string());
  CHECK(identifyPronomFile(file).describe() == "Polynomial Texture Map (fmt/519)");
}

TEST_CASE("PRONOM: JPEG by its JFIF version, or its Exif version when an Exif segment comes first", "[formats][pronom]") {
  requireAsPronom(jpeg(jfif(0)), "fmt/42", "JFIF 1.00");
  requireAsPronom(jpeg(jfif(1)), "fmt/43", "JFIF 1.01");
  requireAsPronom(jpeg(jfif(2)), "fmt/44", "JFIF 1.02");
  requireAsPronom(jpeg(jfif(1) + exif("0230", false)), "fmt/43", "JFIF, then Exif: JFIF");
  requireAsPronom(jpeg(""), "fmt/41", "no JFIF or Exif segment: a raw JPEG stream");
  requireAsPronom(jpeg(jfif(3)), "fmt/41", "JFIF 1.03, which PRONOM does not list");
  for (bool bigEndian : {false, true}) {
    const std::string order = bigEndian ? "big-endian" : "little-endian";
    requireAsPronom(jpeg(exif("0200", bigEndian)), "x-fmt/398", "Exif 2.0 " + order);
    requireAsPronom(jpeg(exif("0210", bigEndian)), "x-fmt/390", "Exif 2.1 " + order);
    requireAsPronom(jpeg(exif("0220", bigEndian)), "x-fmt/391", "Exif 2.2 " + order);
    requireAsPronom(jpeg(exif("0221", bigEndian)), "fmt/645", "Exif 2.21 " + order);
    requireAsPronom(jpeg(exif("0230", bigEndian)), "fmt/1507", "Exif 2.3 " + order);
    requireAsPronom(jpeg(exif("0232", bigEndian)), "fmt/1507", "Exif 2.32 " + order);
    requireAsPronom(jpeg(exif("0300", bigEndian)), "fmt/41", "Exif 3.0, which PRONOM does not list " + order);
  }
  // Without its end-of-image marker within 64 KiB of the end, no JPEG signature matches.
  const std::string cut = jpeg(jfif(1)).substr(0, jpeg(jfif(1)).size() - 2);
  CHECK_FALSE(identifyPronom(cut).identified());
  CHECK(pronom_reference::identify(cut).empty());
}

TEST_CASE("PRONOM: DNG by its DNGVersion tag near the start or the end, TIFF otherwise", "[formats][pronom]") {
  const std::vector<std::string> byMinor = {"fmt/436", "fmt/152", "fmt/437", "fmt/438", "fmt/730", "fmt/1841", "fmt/1842", "fmt/1943"};
  for (bool bigEndian : {false, true})
    for (int minor = 0; minor < static_cast<int>(byMinor.size()); ++minor)
      requireAsPronom(dng(minor, bigEndian), byMinor[minor], "DNG 1." + std::to_string(minor) + (bigEndian ? " MM" : " II"));
  // The tag past the 4080 bytes after the header that the start signatures reach: still DNG,
  // as it lies within 128000 bytes of the end.
  requireAsPronom(dng(4, false, 4080), "fmt/730", "DNGVersion 4086 bytes after the header");
  requireAsPronom(dng(4, false, 4074), "fmt/730", "DNGVersion 4080 bytes after the header");
  // Far from both ends: PRONOM's DNG signatures do not reach it; a TIFF.
  std::string far = dng(4, false, 5000) + std::string(130000, '\0');
  requireAsPronom(far, "fmt/353", "DNGVersion 5000 bytes in, 130000 from the end");
  requireAsPronom(dng(4, false, 5000), "fmt/730", "DNGVersion at the end of the file");
  requireAsPronom(hex("49492A00080000000000") + std::string(64, '\0'), "fmt/353", "a TIFF with no tags");
  requireAsPronom(hex("4D4D002A000000080000") + std::string(64, '\0'), "fmt/353", "a big-endian TIFF");
  requireAsPronom(dng(8, false), "fmt/353", "DNGVersion 1.8, which PRONOM does not list");
}

TEST_CASE("PRONOM: camera raws by their own headers", "[formats][pronom]") {
  requireAsPronom(hex("49492A00100000004352020000000000") + std::string(64, '\0'), "fmt/592", "CR2");
  requireAsPronom(hex("49491A0000004845415043434452") + std::string(64, '\0'), "fmt/593", "CRW");
  // CR3: an ISO box "ftypcrx " and a moov box whose first box, 32 bytes on, is Canon's "CNCV".
  const std::string cr3 = hex("00000018") + "ftypcrx " + std::string(12, '\0') + hex("00000100") + "moov" +
                          std::string(32, '\0') + "CNCV" + std::string(64, '\0');
  requireAsPronom(cr3, "fmt/1595", "CR3");
}

TEST_CASE("PRONOM: PNG by the chunks PRONOM names for 1.1 and 1.2", "[formats][pronom]") {
  requireAsPronom(png({}), "fmt/11", "IHDR, IDAT, IEND");
  requireAsPronom(png({"sRGB"}), "fmt/12", "sRGB");
  requireAsPronom(png({"iCCP"}), "fmt/12", "iCCP");
  requireAsPronom(png({"sPLT"}), "fmt/12", "sPLT");
  requireAsPronom(png({"iTXt"}), "fmt/13", "iTXt");
  requireAsPronom(png({"sRGB", "iTXt"}), "fmt/13", "sRGB and iTXt");
  requireAsPronom(png({"acTL"}), "fmt/935", "acTL: an animated PNG");
  // An animated PNG with an iTXt chunk matches two formats neither of which PRONOM prefers:
  // DROID reports both; Surrogate records none.
  const std::string both = png({"acTL", "iTXt"});
  const formats::PronomIdentity id = identifyPronom(both);
  CHECK_FALSE(id.identified());
  CHECK(id.matches == std::vector<std::string>{"fmt/13", "fmt/935"});
  CHECK(pronom_reference::identify(both) == std::vector<std::string>{"fmt/13", "fmt/935"});
  CHECK(id.describe() == "PRONOM signatures of several formats match: fmt/13, fmt/935");
  // IEND not last: the 1.1 and 1.2 signatures want it at the very end, 1.0's within 4 bytes.
  requireAsPronom(png({"iTXt"}) + "abc", "fmt/11", "three bytes after IEND");
  CHECK_FALSE(identifyPronom(png({"iTXt"}) + "abcde").identified());
}

TEST_CASE("PRONOM: text formats, and files PRONOM has no signature for", "[formats][pronom]") {
  requireAsPronom(std::string("PTM_1.2\nPTM_FORMAT_LRGB\n3\n2\n"), "fmt/519", "PTM 1.2");
  CHECK_FALSE(identifyPronom(std::string("PTM_1.1\nPTM_FORMAT_LRGB\n3\n2\n")).identified());
  requireAsPronom(std::string("<?xml version=\"1.0\" encoding=\"UTF-8\"?>\n<carrier/>\n"), "fmt/101", "XML 1.0");
  requireAsPronom(std::string("<!DOCTYPE html>\n<html><body></body></html>\n"), "fmt/471", "HTML 5");
  // An .lp, an .rti and plain text: no PRONOM signature (x-fmt/111 is named by extension only).
  const formats::PronomIdentity lp = identifyPronom(std::string("3\nIMG_1.jpg 0 0 1\nIMG_2.jpg 0.5 0 0.866\n"));
  CHECK_FALSE(lp.identified());
  CHECK(lp.matches.empty());
  CHECK(lp.describe() == "no PRONOM signature matches");
  CHECK_FALSE(identifyPronom(std::string("#HSH1.2\n3 2 3\n4 4 1\n")).identified());
  CHECK_FALSE(identifyPronom(std::string()).identified());
}

TEST_CASE("PRONOM: a file repeating the start of a signature is read through once", "[formats][pronom]") {
  // Nikon's NEF signatures look for "7C92", then "Nikon" within 35536 bytes, anywhere in a
  // little-endian TIFF. 2 MB of "7C92" took 7 s of CPU (4 MB twice that) before each string's
  // occurrences were remembered (src/formats/pronom.cpp, Bytes); now a fraction of a second.
  std::string bytes = hex("49492A0008000000");
  for (int i = 0; i < 2000000; ++i) bytes += hex("7C92");
  CHECK(identifyPronom(bytes).puid == "fmt/353");
}

TEST_CASE("PRONOM: the name plays no part when a signature matches", "[formats][pronom]") {
  const fs::path dir = fs::temp_directory_path() / "surrogate-test-pronom-names";
  fs::create_directories(dir);
  const fs::path misnamed = dir / "IMG_0001.png";
  std::ofstream(misnamed, std::ios::binary) << jpeg(jfif(1));
  CHECK(identifyPronomFile(misnamed).puid == "fmt/43");
  CHECK_THROWS_WITH(identifyPronomFile(dir / "absent.jpg"), Catch::Contains("cannot be opened"));
}

// Issue 56: the formats PRONOM gives no signature, named as Siegfried and fido name them: text
// is Plain Text File (x-fmt/111), and text named .json or .js is JSON (fmt/817) or JavaScript
// (x-fmt/423). A signature still decides first, and nothing is named text that is not.
TEST_CASE("PRONOM: text, JSON and JavaScript get the PUIDs Siegfried and fido give them", "[formats][pronom]") {
  using formats::identifyPronomNamed;
  const std::string lp = "3\nIMG_1.jpg 0 0 1\nIMG_2.jpg 0.5 0 0.866\nIMG_3.jpg 0 0.5 0.866\n";
  CHECK(identifyPronomNamed(lp, "lights.lp").puid == "x-fmt/111");
  CHECK(identifyPronomNamed(lp, "lights.lp").name == "Plain Text File");
  CHECK(identifyPronomNamed("notes in UTF-8: caf\xc3\xa9\r\n\tend\n", "README.txt").puid == "x-fmt/111");
  CHECK(identifyPronomNamed("{\"type\": \"rti\", \"planes\": 3}\n", "info.json").puid == "fmt/817");
  CHECK(identifyPronomNamed("{\"@context\": []}\n", "ro-crate-metadata.JSON").puid == "fmt/817");
  CHECK(identifyPronomNamed("window.viewerData = {};\n", "viewer-data.js").puid == "x-fmt/423");
  CHECK(identifyPronomNamed("{\"a\": 1}\n", "data.js").puid == "x-fmt/423");
  // The same text with no name is plain text; the signature-only reading finds nothing.
  CHECK(identifyPronomNamed("{\"a\": 1}\n", "").puid == "x-fmt/111");
  CHECK_FALSE(identifyPronom(lp).identified());
  // A signature first: XML named .json stays XML, a PTM stays a PTM.
  CHECK(identifyPronomNamed("<?xml version=\"1.0\"?>\n<a/>\n", "odd.json").puid == "fmt/101");
  CHECK(identifyPronomNamed("PTM_1.2\nPTM_FORMAT_LRGB\n3\n2\n", "a.ptm").puid == "fmt/519");
  // Not text: a NUL, another control character, bytes that are not UTF-8, nothing at all.
  CHECK_FALSE(identifyPronomNamed(std::string("{\"a\": 1}\0\n", 10), "info.json").identified());
  CHECK_FALSE(identifyPronomNamed("line\x01\n", "a.lp").identified());
  CHECK_FALSE(identifyPronomNamed("caf\xe9\n", "a.txt").identified());
  CHECK_FALSE(identifyPronomNamed("", "empty.json").identified());
  // The description says how it was named.
  CHECK(identifyPronomNamed(lp, "lights.lp").describe() ==
        "Plain Text File (x-fmt/111, named from its text as Siegfried and fido name it: PRONOM gives it no signature)");
  CHECK_THAT(identifyPronomNamed("{}\n", "info.json").describe(),
             Catch::Contains("JSON Data Interchange Format (fmt/817, named from its text and its name's extension"));

  // identifyPronomFile names a file by its own name.
  const fs::path dir = fs::temp_directory_path() / "surrogate-test-pronom-text";
  fs::create_directories(dir);
  std::ofstream(dir / "lights.lp", std::ios::binary) << lp;
  std::ofstream(dir / "info.json", std::ios::binary) << "{\"planes\": 3}\n";
  std::ofstream(dir / "viewer-data.js", std::ios::binary) << "var data = 1;\n";
  CHECK(identifyPronomFile(dir / "lights.lp").puid == "x-fmt/111");
  CHECK(identifyPronomFile(dir / "info.json").puid == "fmt/817");
  CHECK(identifyPronomFile(dir / "viewer-data.js").puid == "x-fmt/423");
}

TEST_CASE("PRONOM: a sequence sought anywhere is found at every place, up to the last bytes", "[formats][pronom]") {
  // src/formats/pronom.cpp seeks such sequences 16 places at a time and skips PNG 1.1's
  // searches once PNG 1.2 has matched: a chunk name at every offset of a long IDAT, across block
  // edges and up to the IEND, must give what DROID's reading of the signatures gives.
  const std::string head = hex("89504E470D0A1A0A0000000D49484452000000010000000108000000003A7E9B55");
  const std::string tail = hex("0000000049454E44AE426082");
  for (const std::string& chunk : {std::string("acTL"), std::string("sRGB"), std::string("iCCP")}) {
    for (const bool itxt : {false, true}) {
      const std::string start = head + (itxt ? hex("00000001") + "iTXt" + "x" + hex("00000000") : std::string());
      for (std::size_t at = 0; at <= 40; ++at) {
        std::string idat(40, '\x5A');  // near misses: the chunk's first and last bytes around it
        idat[0] = chunk[0];
        idat[39] = chunk[3];
        idat.replace(at, std::min<std::size_t>(4, 40 - at), chunk.substr(0, std::min<std::size_t>(4, 40 - at)));
        const std::string bytes = start + idat + tail;
        INFO(chunk + (itxt ? " after iTXt" : "") + " at " + std::to_string(at));
        CHECK(identifyPronom(bytes).matches == pronom_reference::identify(bytes));
      }
    }
  }
  // A chunk name only in a PNG's last bytes, past hundreds of blocks of compressed-like bytes.
  std::string idat;
  for (int i = 0; i < 100000; ++i) idat.push_back(static_cast<char>((i * 167 + 13) % 251));
  for (const std::string& chunk : {std::string("acTL"), std::string("sPLT")}) {
    const std::string bytes = head + hex("00000001") + "iTXt" + "x" + hex("00000000") + idat + chunk + tail;
    INFO(chunk);
    CHECK(identifyPronom(bytes).matches == pronom_reference::identify(bytes));
  }
}
