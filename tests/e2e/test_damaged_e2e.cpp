// Issue 13, decoding: what `surrogate run` does with images whose data is damaged, whose headers
// declare absurd sizes, or whose names lie about their format, as a user meets it.
//
//   - damaged data (half a JPEG with its end marker re-appended, flipped bits, a PNG chunk's
//     broken CRC, a TIFF strip cut short, a DNG tile overwritten): exit 1 naming the file and
//     the decoding library's words; with --accept-damaged IMAGE --reason "..." the run completes
//     and the carrier records the intervention (who, when, why, the bytes accepted), the
//     library's words (imageValue decoderWarning) and a log entry; the decision stands for later
//     runs until withdrawn with --forget-damaged.
//   - headers declaring 30000x30000 or 20000x20000 pixels: refused in well under a second,
//     within a memory limit far below what decoding would take.
//   - a PNG named .jpg: recorded as image/png / PNG, with a warning.
#include <catch2/catch.hpp>

#include <chrono>
#include <fstream>

#include <tiffio.h>

#include "../image/damage.h"
#include "carrier/carrier.h"
#include "core/digest.h"
#include "e2e_support.h"
#include "image/decode.h"

namespace fs = std::filesystem;
using namespace surrogate;

namespace {

carrier::Carrier carrierOf(const fs::path& capture) {
  return carrier::loadCarrier(capture / "assembly-files/carrier.xml");
}

e2e::CommandResult run(const fs::path& capture, const std::string& options = "") {
  return e2e::surrogate("run " + e2e::quote(capture) + " --quiet --no-report " + options);
}

const carrier::Step& decodeStep(const carrier::Carrier& c) {
  for (const carrier::Step& s : c.process)
    if (s.component == "ImageDecode") return s;
  throw std::runtime_error("no ImageDecode step");
}

// The decoderWarning recorded for `path`, or "".
std::string decoderWarning(const carrier::Carrier& c, const std::string& path) {
  const carrier::FileRecord* f = c.findFileByPath(path);
  REQUIRE(f);
  for (const carrier::Result& r : c.data)
    for (const carrier::DataItem* i : r.itemsOf("imageValue"))
      if (i->get("image") == f->id && i->get("name") == std::string("decoderWarning")) return *i->get("value");
  return "";
}

// Refused: exit 1, the file named, the library's words, and what to do.
void requireRefused(const e2e::CommandResult& r, const std::string& path, const std::string& words) {
  INFO(r.output);
  CHECK(r.exitCode == 1);
  CHECK_THAT(r.output, Catch::Contains(path));
  CHECK_THAT(r.output, Catch::Contains(words));
  CHECK_THAT(r.output, Catch::Contains("--accept-damaged " + path));
}

// Accepted: exit 0, the intervention on ImageDecode naming the file's bytes, and the words.
void requireAccepted(const e2e::CommandResult& r, const fs::path& capture, const std::string& path,
                     const std::string& reason, const std::string& words) {
  INFO(r.output);
  REQUIRE(r.exitCode == 0);
  const carrier::Carrier c = carrierOf(capture);
  bool recorded = false;
  for (const carrier::Intervention& i : decodeStep(c).interventions)
    if (i.kind == "accept-decoder-warning" && i.target == path) {
      recorded = true;
      CHECK(i.reason == reason);
      CHECK(i.value == "sha256:" + digestFile(capture / path).sha256);
      CHECK_FALSE(i.who.empty());
      CHECK_FALSE(i.time.empty());
    }
  CHECK(recorded);
  CHECK_THAT(decoderWarning(c, path), Catch::Contains(words));
  bool logged = false;
  for (const carrier::LogEntry& e : c.log)
    logged = logged || (e.level == "intervention" && e.text.find(path) != std::string::npos &&
                        e.text.find(words) != std::string::npos && e.text.find(reason) != std::string::npos);
  CHECK(logged);
}

// An export decoded (8-bit RGB) as an Image, to write it again in another format.
Image exportPixels(const fs::path& file) { return image::decodeImage(file, image::RawDecodeSettings()); }

void writeTiffStrips(const Image& im, const fs::path& path) {
  TIFF* t = TIFFOpen(path.c_str(), "w");
  REQUIRE(t);
  TIFFSetField(t, TIFFTAG_IMAGEWIDTH, im.width);
  TIFFSetField(t, TIFFTAG_IMAGELENGTH, im.height);
  TIFFSetField(t, TIFFTAG_BITSPERSAMPLE, 8);
  TIFFSetField(t, TIFFTAG_SAMPLESPERPIXEL, 3);
  TIFFSetField(t, TIFFTAG_PHOTOMETRIC, PHOTOMETRIC_RGB);
  TIFFSetField(t, TIFFTAG_PLANARCONFIG, PLANARCONFIG_CONTIG);
  TIFFSetField(t, TIFFTAG_COMPRESSION, COMPRESSION_NONE);
  TIFFSetField(t, TIFFTAG_ROWSPERSTRIP, 32);
  std::vector<std::uint8_t> row(static_cast<std::size_t>(im.width) * 3);
  for (int y = 0; y < im.height; ++y) {
    for (int x = 0; x < im.width; ++x)
      for (int c = 0; c < 3; ++c) row[3 * x + c] = static_cast<std::uint8_t>(im.at(x, y, c) / 257);
    TIFFWriteScanline(t, row.data(), y, 0);
  }
  TIFFClose(t);
}

double secondsOf(const std::function<void()>& f) {
  const auto start = std::chrono::steady_clock::now();
  f();
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

}  // namespace

TEST_CASE("a JPEG export with half its data missing and its end marker re-appended is refused, then accepted on the record") {
  const fs::path capture = e2e::smallCapture(e2e::freshDir("damaged-half-jpeg"));
  const std::string path = "jpeg-exports/IMG_0003.jpg";
  test::writeBytes(capture / path, test::halfJpeg(test::readBytes(capture / path)));

  requireRefused(run(capture, "--source export"), path, "libjpeg reports \"Corrupt JPEG data: premature end of data segment\"");
  const std::string reason = "the only frame lit from the north-west; its lower half is lost";
  requireAccepted(run(capture, "--source export --accept-damaged IMG_0003 --reason \"" + reason + "\""), capture, path,
                  reason, "libjpeg: Corrupt JPEG data: premature end of data segment");
  const carrier::Carrier accepted = carrierOf(capture);
  REQUIRE(decodeStep(accepted).interventions.size() == 1);
  const std::string time = decodeStep(accepted).interventions[0].time;

  // The decision stands: a plain run keeps it, with its first time.
  const e2e::CommandResult again = run(capture);
  INFO(again.output);
  REQUIRE(again.exitCode == 0);
  REQUIRE(decodeStep(carrierOf(capture)).interventions.size() == 1);
  CHECK(decodeStep(carrierOf(capture)).interventions[0].time == time);
  CHECK_FALSE(decoderWarning(carrierOf(capture), path).empty());

  // Withdrawn, with a reason: refused again; the failed run is in the history.
  requireRefused(run(capture, "--forget-damaged IMG_0003 --reason \"re-shot instead\""), path, "premature end of data segment");
  const carrier::Carrier after = carrierOf(capture);
  REQUIRE_FALSE(after.header.runs.empty());
  CHECK(after.header.runs.back().outcome == "failed");
}

TEST_CASE("bit-flipped JPEG exports that libjpeg warns about are refused, and accepted on the record") {
  const fs::path capture = e2e::smallCapture(e2e::freshDir("damaged-flipped"));
  const fs::path scratch = e2e::freshDir("damaged-flipped-probe");
  std::vector<std::string> damaged;
  for (const char* name : {"IMG_0002.jpg", "IMG_0005.jpg", "IMG_0007.jpg"}) {
    const std::string path = std::string("jpeg-exports/") + name;
    const std::string whole = test::readBytes(capture / path);
    // The first few flips libjpeg notices (not every flip is noticeable: a flipped bit can make
    // another valid code).
    for (std::uint32_t seed = 1;; ++seed) {
      REQUIRE(seed < 200);
      const std::string flipped = test::flipJpegBits(whole, seed, 3);
      test::writeBytes(scratch / name, flipped);
      try {
        image::decodeImage(scratch / name, image::RawDecodeSettings());
      } catch (const image::DamagedImageError&) {
        test::writeBytes(capture / path, flipped);
        break;
      } catch (const Error&) {
      }
    }
    damaged.push_back(path);
  }
  requireRefused(run(capture, "--source export"), damaged.front(), "libjpeg reports \"Corrupt JPEG data");
  std::string accept;
  for (const std::string& p : damaged) accept += " --accept-damaged " + p + " --reason \"card reader fault; no other copy\"";
  const e2e::CommandResult r = run(capture, "--source export" + accept);
  INFO(r.output);
  REQUIRE(r.exitCode == 0);
  for (const std::string& p : damaged) requireAccepted(r, capture, p, "card reader fault; no other copy", "libjpeg: Corrupt JPEG data");
}

TEST_CASE("a PNG export with a broken chunk CRC and a TIFF export with a strip cut short are refused, then accepted") {
  const fs::path capture = e2e::smallCapture(e2e::freshDir("damaged-png-tiff"));
  const Image four = exportPixels(capture / "jpeg-exports/IMG_0004.jpg");
  const Image six = exportPixels(capture / "jpeg-exports/IMG_0006.jpg");
  fs::remove(capture / "jpeg-exports/IMG_0004.jpg");
  fs::remove(capture / "jpeg-exports/IMG_0006.jpg");
  const fs::path scratch = e2e::freshDir("damaged-png-tiff-sound");
  image::writePng(four, scratch / "IMG_0004.png");
  test::writeBytes(capture / "jpeg-exports/IMG_0004.png", test::pngWithBadCrc(test::readBytes(scratch / "IMG_0004.png")));
  writeTiffStrips(six, scratch / "IMG_0006.tif");
  test::writeBytes(capture / "jpeg-exports/IMG_0006.tif", test::tiffWithShortStrip(test::readBytes(scratch / "IMG_0006.tif")));

  requireRefused(run(capture, "--source export"), "jpeg-exports/IMG_0004.png", "libpng reports \"IDAT: CRC error\"");
  const e2e::CommandResult png = run(capture, "--source export --accept-damaged IMG_0004.png --reason \"CRC only\"");
  requireRefused(png, "jpeg-exports/IMG_0006.tif", "libtiff reports");
  const e2e::CommandResult both = run(capture, "--source export --accept-damaged IMG_0004.png --reason \"CRC only\" "
                                               "--accept-damaged jpeg-exports/IMG_0006.tif --reason \"bottom rows lost\"");
  requireAccepted(both, capture, "jpeg-exports/IMG_0004.png", "CRC only", "libpng: IDAT: CRC error");
  requireAccepted(both, capture, "jpeg-exports/IMG_0006.tif", "bottom rows lost", "libtiff: ");
}

TEST_CASE("a DNG original with a corrupt lossless-JPEG tile is refused with LibRaw's words, then accepted") {
  // A dome capture (lights from its .lp) of eight lossless-JPEG DNGs, one with a damaged tile.
  const fs::path capture = e2e::freshDir("damaged-dng") / "capture";
  fs::create_directories(capture / "original-captures");
  const test::LosslessDng dng = test::losslessDng(64, 48);
  std::ofstream lp(capture / "dome.lp");
  lp << "8\n";
  for (int i = 1; i <= 8; ++i) {
    const std::string name = "IMG_000" + std::to_string(i) + ".dng";
    test::writeBytes(capture / "original-captures" / name, i == 5 ? test::dngWithCorruptTile(dng, 3) : dng.bytes);
    const double a = 0.785398 * i;
    lp << name << " " << 0.7 * std::cos(a) << " " << 0.7 * std::sin(a) << " 0.714\n";
  }
  lp.close();
  const std::string path = "original-captures/IMG_0005.dng";
  requireRefused(run(capture, "--lp dome.lp"), path, "LibRaw reports \"corrupt raw data");
  requireAccepted(run(capture, "--lp dome.lp --accept-damaged IMG_0005 --reason \"bad sector; the card is gone\""),
                  capture, path, "bad sector; the card is gone", "LibRaw: corrupt raw data");
}

TEST_CASE("images whose headers declare huge sizes are refused at once, within a small memory limit") {
  const fs::path sample = e2e::freshDir("huge-sample");
  Image tiny(16, 16, 3);
  tiny.bitsPerSample = 8;
  image::writeJpeg(tiny, sample / "tiny.jpg", 90);
  const std::string jpeg = test::readBytes(sample / "tiny.jpg");
  // A generous limit for the process itself, far below 16 decoded images of these sizes.
  const std::string limit = "ulimit -v 3000000; ";
  struct Case {
    const char* name;
    int side;
    bool png;
    int exitCode;
    const char* says;
  };
  for (const Case& k : {Case{"jpeg-30000", 30000, false, 1, "500 Mpx"}, Case{"jpeg-20000", 20000, false, 2, "--memory"},
                        Case{"png-20000", 20000, true, 2, "--memory"}}) {
    INFO(k.name);
    const fs::path capture = e2e::freshDir(std::string("huge-") + k.name) / "capture";
    fs::create_directories(capture / "jpeg-exports");
    for (int i = 1; i <= 16; ++i) {
      const std::string stem = "IMG_" + std::string(i < 10 ? "000" : "00") + std::to_string(i);
      if (k.png) test::writeBytes(capture / "jpeg-exports" / (stem + ".png"), test::pngDeclaring(k.side, k.side));
      else test::writeBytes(capture / "jpeg-exports" / (stem + ".jpg"), test::jpegDeclaring(jpeg, k.side, k.side));
    }
    e2e::CommandResult r;
    const double seconds = secondsOf([&] {
      r = e2e::runShell(limit + e2e::quote(SURROGATE_EXE) + " run " + e2e::quote(capture) + " --quiet --memory 2G");
    });
    INFO(r.output);
    CHECK(r.exitCode == k.exitCode);
    CHECK_THAT(r.output, Catch::Contains(std::to_string(k.side) + "x" + std::to_string(k.side)));
    CHECK_THAT(r.output, Catch::Contains(k.says));
    CHECK(seconds < 1.0);
  }
}

TEST_CASE("a PNG named .jpg is recorded as image/png from its content, with a warning") {
  const fs::path capture = e2e::smallCapture(e2e::freshDir("png-named-jpg"));
  const std::string path = "jpeg-exports/IMG_0002.jpg";
  const Image pixels = exportPixels(capture / path);
  const fs::path scratch = e2e::freshDir("png-named-jpg-png");
  image::writePng(pixels, scratch / "IMG_0002.png");
  fs::copy_file(scratch / "IMG_0002.png", capture / path, fs::copy_options::overwrite_existing);
  const e2e::CommandResult r = run(capture, "--source export");
  INFO(r.output);
  REQUIRE(r.exitCode == 0);
  const carrier::Carrier c = carrierOf(capture);
  const carrier::FileRecord* f = c.findFileByPath(path);
  REQUIRE(f);
  CHECK(f->mediaType == "image/png");
  CHECK(f->format == "PNG");
  CHECK(c.findFileByPath("jpeg-exports/IMG_0003.jpg")->mediaType == "image/jpeg");
  bool warned = false;
  for (const carrier::LogEntry& e : c.log)
    warned = warned || (e.level == "warning" && e.text.find(path + " is a PNG file named .jpg") != std::string::npos);
  CHECK(warned);
}
