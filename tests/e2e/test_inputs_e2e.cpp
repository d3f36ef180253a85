// Issue 13 (light estimation and the commands' inputs): ordinary but wrong input is refused
// with exit 1 or 2 and a message naming the image, file or option and what to do, never an
// internal error (exit 5) and never a confident result made from garbage.
//
//   - a frame whose sphere shows no highlight (flat grey, saturated white) stops the run
//     naming the image, until it is excluded or its highlight is given by hand; a circle
//     given by hand away from the sphere stops it naming --sphere; the generated captures
//     run with every highlight confident (no false refusal);
//   - render and fit outputs: a folder, a missing folder, an unknown extension; render writes
//     the format its output's name says (PNG, JPEG, TIFF);
//   - --threads out of range, --resize to a few pixels, an .lp with an absurdly long name,
//     an .rti declaring another basis type or element size;
//   - capture file names that are not UTF-8, symbolic link loops.
#include <catch2/catch.hpp>

#include <unistd.h>

#include <opencv2/core.hpp>
#include <opencv2/imgcodecs.hpp>

#include <fstream>
#include <string>

#include "carrier/carrier.h"
#include "e2e_support.h"
#include "formats/rti_hsh.h"

namespace fs = std::filesystem;
using namespace surrogate;

namespace {

void requireRefused(const e2e::CommandResult& r, const std::vector<std::string>& named, bool usage = false) {
  INFO(r.output);
  if (usage) CHECK(r.exitCode == 2);
  else CHECK(r.exitCode == 1);
  CHECK_THAT(r.output, !Catch::Contains("internal error"));
  for (const std::string& n : named) CHECK_THAT(r.output, Catch::Contains(n));
}

// Replaces an export of the small capture by a uniform picture of the same size (400x300).
void uniformExport(const fs::path& capture, const std::string& stem, int value) {
  const cv::Mat m(300, 400, CV_8UC3, cv::Scalar(value, value, value));
  REQUIRE(cv::imwrite((capture / "jpeg-exports" / (stem + ".jpg")).string(), m, {cv::IMWRITE_JPEG_QUALITY, 95}));
}

carrier::Carrier carrierOf(const fs::path& capture) {
  return carrier::loadCarrier(capture / "assembly-files/carrier.xml");
}

// Pointers into `c`: keep the carrier alive while using them.
std::vector<const carrier::DataItem*> items(const carrier::Carrier& c, const std::string& element) {
  std::vector<const carrier::DataItem*> out;
  for (const carrier::Result& r : c.data)
    for (const carrier::DataItem* d : r.itemsOf(element)) out.push_back(d);
  return out;
}

// One processed small capture for the tests that only read its results.
fs::path processedCapture() {
  static fs::path capture;
  if (capture.empty()) {
    capture = e2e::smallCapture(e2e::freshDir("inputs-processed"));
    const e2e::CommandResult r = e2e::surrogate("run " + e2e::quote(capture) + " --quiet");
    INFO(r.output);
    REQUIRE(r.exitCode == 0);
  }
  return capture;
}

std::string head(const fs::path& file, std::size_t n) { return e2e::bytesOf(file).substr(0, n); }

}  // namespace

// ---- Highlights ------------------------------------------------------------------------------

TEST_CASE("the generated captures run with every highlight confident: no false refusal") {
  for (const int images : {8, 12}) {
    for (const char* source : {"original", "export"}) {
      const fs::path capture = e2e::smallCapture(e2e::freshDir("inputs-confident"), images);
      const e2e::CommandResult r =
          e2e::surrogate("lights " + e2e::quote(capture) + " -o " + e2e::quote(capture.parent_path() / "l.lp") +
                         " --quiet --source " + source);
      INFO(images << " images, " << source << "\n" << r.output);
      REQUIRE(r.exitCode == 0);
      const carrier::Carrier c = carrierOf(capture);
      const auto highlights = items(c, "highlight");
      REQUIRE(static_cast<int>(highlights.size()) == images);
      for (const carrier::DataItem* h : highlights) {
        CHECK(h->get("flag") == std::optional<std::string>("ok"));
        REQUIRE(h->get("confidence"));
        CHECK(h->number("confidence") >= 0.9);  // measured: 1 for every one
        CHECK_FALSE(h->get("reason"));
      }
    }
  }
}

TEST_CASE("a flat grey frame stops the run naming the image, and runs once it is excluded") {
  const fs::path capture = e2e::smallCapture(e2e::freshDir("inputs-grey"));
  uniformExport(capture, "IMG_0003", 128);
  const e2e::CommandResult r = e2e::surrogate("run " + e2e::quote(capture) + " --quiet --source export");
  requireRefused(r, {"jpeg-exports/IMG_0003.jpg", "flat", "no trustworthy highlight", "--exclude IMG_0003",
                     "--highlight IMG_0003:sphere1=X,Y"});
  CHECK_THAT(r.output, !Catch::Contains("IMG_0004"));
  CHECK_FALSE(fs::exists(capture / "finished-files"));
  // The refused highlight is in the carrier with its flag, confidence 0 and the reason.
  bool recorded = false;
  const carrier::Carrier failed = carrierOf(capture);
  for (const carrier::DataItem* h : items(failed, "highlight"))
    if (h->get("flag") == std::optional<std::string>("flat")) {
      recorded = true;
      CHECK(h->number("confidence") == 0);
      CHECK_THAT(h->get("reason").value_or(""), Catch::Contains("no peak"));
    }
  CHECK(recorded);

  const e2e::CommandResult ok = e2e::surrogate("run " + e2e::quote(capture) + " --quiet --source export " +
                                               "--exclude IMG_0003 --reason \"the flash did not fire\"");
  INFO(ok.output);
  REQUIRE(ok.exitCode == 0);
  CHECK(items(carrierOf(capture), "light").size() == 7);
}

TEST_CASE("a saturated white frame stops the run, and runs with its highlight given by hand") {
  const fs::path capture = e2e::smallCapture(e2e::freshDir("inputs-white"));
  uniformExport(capture, "IMG_0005", 255);
  const e2e::CommandResult r = e2e::surrogate("run " + e2e::quote(capture) + " --quiet --source export --json");
  requireRefused(r, {"IMG_0005", "saturated", "--exclude IMG_0005", "--highlight IMG_0005:sphere1=X,Y"});
  CHECK_THAT(r.output, Catch::Contains("\"file\":\"jpeg-exports/IMG_0005.jpg\""));

  // With its highlight given, the white frame still cannot be fitted: the model misses it far
  // more than the others, and the run says so (check residual-outlier) unless that is accepted.
  const e2e::CommandResult fitted = e2e::surrogate(
      "run " + e2e::quote(capture) +
      " --quiet --source export --highlight IMG_0005:0=339,57 --reason \"overexposed, taken from the log\"");
  CHECK(fitted.exitCode == 1);
  CHECK_THAT(fitted.output, Catch::Contains("residual-outlier") && Catch::Contains("--exclude IMG_0005"));
  const e2e::CommandResult ok = e2e::surrogate(
      "run " + e2e::quote(capture) +
      " --quiet --source export --highlight IMG_0005:0=339,57 --reason \"overexposed, taken from the log\" "
      "--accept residual-outlier --reason \"a test of the record\"");
  INFO(ok.output);
  REQUIRE(ok.exitCode == 0);
  int manual = 0;
  const carrier::Carrier c = carrierOf(capture);
  for (const carrier::DataItem* h : items(c, "highlight"))
    if (h->get("flag") == std::optional<std::string>("manual")) {
      ++manual;
      CHECK(h->number("confidence") == 1);
      CHECK_THAT(h->get("reason").value_or(""), Catch::Contains("overexposed"));
    }
  CHECK(manual == 1);
  CHECK(items(c, "light").size() == 8);
}

TEST_CASE("several refused frames are named in one message") {
  const fs::path capture = e2e::smallCapture(e2e::freshDir("inputs-two"));
  uniformExport(capture, "IMG_0002", 128);
  uniformExport(capture, "IMG_0006", 255);
  const e2e::CommandResult r = e2e::surrogate("lights " + e2e::quote(capture) + " -o " +
                                              e2e::quote(capture.parent_path() / "x.lp") + " --quiet --source export");
  requireRefused(r, {"2 images", "IMG_0002.jpg (flat", "IMG_0006.jpg (saturated"});
  CHECK_FALSE(fs::exists(capture.parent_path() / "x.lp"));
}

TEST_CASE("a refusal names every frame it refuses, however many") {
  // 10 flat frames of 24: each is named (the message once named 8 "and 2 more"). The sphere is
  // given (the generator's circle), as flat frames in the median would hide it from detection.
  const fs::path capture = e2e::smallCapture(e2e::freshDir("inputs-ten"), 24);
  std::vector<std::string> flat;
  for (int n = 2; n <= 20; n += 2) {
    const std::string stem = std::string(n < 10 ? "IMG_000" : "IMG_00") + std::to_string(n);
    uniformExport(capture, stem, 128);
    flat.push_back("jpeg-exports/" + stem + ".jpg (flat");
  }
  flat.push_back("10 images");
  const e2e::CommandResult r = e2e::surrogate("lights " + e2e::quote(capture) + " -o " +
                                              e2e::quote(capture.parent_path() / "x.lp") +
                                              " --quiet --source export --sphere 339,57,45 --reason measured");
  requireRefused(r, flat);
  CHECK_THAT(r.output, !Catch::Matches(".*and [0-9]+ more.*", Catch::CaseSensitive::Yes));

  // Most frames without a highlight: the sphere is refused, naming all 5 frames.
  const fs::path few = e2e::smallCapture(e2e::freshDir("inputs-five"));
  std::vector<std::string> five{"5 of 8 images"};
  for (int n = 1; n <= 5; ++n) {
    uniformExport(few, "IMG_000" + std::to_string(n), 128);
    five.push_back("IMG_000" + std::to_string(n));
  }
  const e2e::CommandResult sphere = e2e::surrogate("lights " + e2e::quote(few) + " -o " +
                                                   e2e::quote(few.parent_path() / "x.lp") +
                                                   " --quiet --source export --sphere 339,57,45 --reason measured");
  requireRefused(sphere, five);
  CHECK_THAT(sphere.output, !Catch::Matches(".*and [0-9]+ more.*", Catch::CaseSensitive::Yes));
}

TEST_CASE("a circle given by hand away from the sphere stops the run naming --sphere") {
  // The sphere of the small capture is at about (339, 57), radius 45.
  const fs::path capture = e2e::smallCapture(e2e::freshDir("inputs-wrong-sphere"));
  const e2e::CommandResult r =
      e2e::surrogate("run " + e2e::quote(capture) + " --quiet --sphere 60,240,40 --reason x --json");
  requireRefused(r, {"--sphere 60,240,40", "no trustworthy highlight in", "--forget-sphere sphere1"});
  CHECK_THAT(r.output, Catch::Contains("\"file\":\"--sphere 60,240,40\""));
  CHECK_FALSE(fs::exists(capture / "finished-files"));
  // Given again where the sphere is, the capture runs.
  const e2e::CommandResult ok = e2e::surrogate("run " + e2e::quote(capture) +
                                               " --quiet --forget-sphere sphere1 --reason \"typed the wrong corner\"");
  INFO(ok.output);
  CHECK(ok.exitCode == 0);
}

// ---- render and fit outputs ------------------------------------------------------------------

TEST_CASE("render writes the format its output's name says: PNG, JPEG, TIFF") {
  const fs::path capture = processedCapture();
  const fs::path dir = e2e::freshDir("inputs-render");
  const std::string model = e2e::quote(capture / "finished-files/ptm-lrgb.ptm");
  const std::string light = " --light 0.3,0.2,0.9 -o ";
  struct Out {
    const char* name;
    std::string magic;
  };
  for (const Out& o : {Out{"a.png", "\x89PNG"}, Out{"b.jpg", "\xFF\xD8\xFF"}, Out{"c.JPEG", "\xFF\xD8\xFF"},
                       Out{"d.tif", "II*"}, Out{"e.tiff", "II*"}}) {
    const e2e::CommandResult r = e2e::surrogate("render " + model + light + e2e::quote(dir / o.name));
    INFO(o.name << "\n" << r.output);
    CHECK(r.exitCode == 0);
    CHECK(head(dir / o.name, o.magic.size()) == o.magic);
  }
  // JPEG quality: a lower one gives a smaller file; only for JPEG output.
  REQUIRE(e2e::surrogate("render " + model + light + e2e::quote(dir / "q.jpg") + " --quality 40").exitCode == 0);
  CHECK(fs::file_size(dir / "q.jpg") < fs::file_size(dir / "b.jpg"));
  requireRefused(e2e::surrogate("render " + model + light + e2e::quote(dir / "f.png") + " --quality 40"),
                 {"--quality 40", "JPEG output only"}, true);
  requireRefused(e2e::surrogate("render " + model + light + e2e::quote(dir / "g.jpg") + " --quality 0"),
                 {"--quality 0", "1 to 100"}, true);
  // Any other name is refused before anything is written.
  requireRefused(e2e::surrogate("render " + model + light + e2e::quote(dir / "h.bmp")), {"h.bmp", ".png", ".jpg", ".tif"},
                 true);
  CHECK_FALSE(fs::exists(dir / "h.bmp"));
}

TEST_CASE("render into a folder or a missing folder is refused naming the path") {
  const fs::path capture = processedCapture();
  const fs::path dir = e2e::freshDir("inputs-render-paths");
  const std::string model = e2e::quote(capture / "finished-files/hsh2.rti");
  fs::create_directories(dir / "out.png");
  requireRefused(e2e::surrogate("render " + model + " --light 0,0,1 -o " + e2e::quote(dir / "out.png")),
                 {(dir / "out.png").string(), "is a folder"}, true);
  requireRefused(e2e::surrogate("render " + model + " --light 0,0,1 -o " + e2e::quote(dir)), {dir.string()}, true);
  requireRefused(e2e::surrogate("render " + model + " --light 0,0,1 -o " + e2e::quote(dir / "missing/x.png")),
                 {(dir / "missing").string(), "does not exist"}, true);
  CHECK_FALSE(fs::exists(dir / "missing"));
}

TEST_CASE("fit into a missing folder or onto a folder is refused before any fitting") {
  const fs::path capture = processedCapture();
  const fs::path dir = e2e::freshDir("inputs-fit-paths");
  const std::string lp = e2e::quote(capture / "assembly-files/lights.lp");
  requireRefused(e2e::surrogate("fit --lp " + lp + " -o " + e2e::quote(dir / "missing/m.ptm")),
                 {(dir / "missing").string(), "does not exist"}, true);
  fs::create_directories(dir / "m.rti");
  requireRefused(e2e::surrogate("fit --lp " + lp + " -o " + e2e::quote(dir / "m.rti")), {"m.rti", "is a folder"}, true);
  CHECK_FALSE(fs::exists(dir / "missing"));
}

TEST_CASE("lights and report outputs in a missing folder or onto a folder are refused before any work") {
  const fs::path capture = e2e::smallCapture(e2e::freshDir("inputs-outputs"));
  const fs::path dir = capture.parent_path();
  requireRefused(e2e::surrogate("lights " + e2e::quote(capture) + " -o " + e2e::quote(dir / "missing/x.lp") + " --quiet"),
                 {(dir / "missing").string(), "does not exist"}, true);
  CHECK_FALSE(fs::exists(capture / "assembly-files"));  // refused before the light estimation ran
  fs::create_directories(dir / "r.html");
  requireRefused(e2e::surrogate("report " + e2e::quote(processedCapture()) + " -o " + e2e::quote(dir / "r.html")),
                 {"r.html", "is a folder"}, true);
  requireRefused(e2e::surrogate("report " + e2e::quote(processedCapture()) + " -o " + e2e::quote(dir / "no/r.html")),
                 {(dir / "no").string(), "does not exist"}, true);
}

// ---- Option values ---------------------------------------------------------------------------

TEST_CASE("threads below 0 or absurdly high are refused for fit, render and run") {
  const fs::path capture = processedCapture();
  const fs::path dir = e2e::freshDir("inputs-threads");
  const std::string lp = e2e::quote(capture / "assembly-files/lights.lp");
  const std::string model = e2e::quote(capture / "finished-files/ptm-lrgb.ptm");
  for (const char* n : {"-1", "100000", "two"}) {
    const std::string threads = std::string(" --threads ") + n;
    requireRefused(e2e::surrogate("fit --lp " + lp + " -o " + e2e::quote(dir / "m.ptm") + threads), {"--threads"}, true);
    requireRefused(e2e::surrogate("render " + model + " --light 0,0,1 -o " + e2e::quote(dir / "r.png") + threads),
                   {"--threads"}, true);
    requireRefused(e2e::surrogate("run " + e2e::quote(capture) + " --quiet" + threads), {"--threads"}, true);
  }
  CHECK_FALSE(fs::exists(dir / "m.ptm"));
  CHECK_FALSE(fs::exists(dir / "r.png"));
}

TEST_CASE("a resize to a few pixels is refused naming the option, before any step runs") {
  const fs::path capture = e2e::smallCapture(e2e::freshDir("inputs-resize"));
  requireRefused(e2e::surrogate("run " + e2e::quote(capture) + " --quiet --resize 1e-320"),
                 {"--resize 1e-320", "1x1", "16 pixels"}, true);
  requireRefused(e2e::surrogate("run " + e2e::quote(capture) + " --quiet --resize 0.02"), {"--resize 0.02", "8x6"},
                 true);
  requireRefused(e2e::surrogate("run " + e2e::quote(capture) + " --quiet --resize 8x8"), {"--resize 8x8", "16x16"},
                 true);
  requireRefused(e2e::surrogate("run " + e2e::quote(capture) + " --quiet --crop 0,100,100,100 --resize 0.1"),
                 {"--resize 0.1", "10x10"}, true);
  CHECK_FALSE(fs::exists(capture / "finished-files"));
  CHECK_FALSE(fs::exists(capture / "assembly-files"));
}

// ---- Files the commands read -----------------------------------------------------------------

TEST_CASE("an .lp naming an absurdly long file name is refused naming the .lp") {
  const fs::path dir = e2e::freshDir("inputs-long-lp");
  {
    std::ofstream lp(dir / "long.lp", std::ios::binary);
    lp << "1\n" << std::string(20 * 1000 * 1000, 'a') << ".jpg 0 0 1\n";
  }
  const e2e::CommandResult r = e2e::surrogate("fit --lp " + e2e::quote(dir / "long.lp") + " -o " +
                                              e2e::quote(dir / "m.ptm"));
  requireRefused(r, {"long.lp", "line 2", "4096"});
  CHECK(r.output.size() < 2000);
}

TEST_CASE("an .rti declaring another basis type or element size is refused, not rendered") {
  const fs::path dir = e2e::freshDir("inputs-rti");
  formats::HshFile hsh;
  hsh.width = 4;
  hsh.height = 3;
  hsh.terms = 4;
  hsh.scale.assign(4, 1.0f);
  hsh.bias.assign(4, 0.0f);
  hsh.coefficients.assign(hsh.texels() * 3 * 4, 100);
  const std::string good = formats::serializeRti(hsh);
  const std::string line = "4 2 1\n";
  REQUIRE(good.find(line) != std::string::npos);
  for (const std::string& declared : {std::string("4 99 1\n"), std::string("4 2 0\n")}) {
    std::string bad = good;
    bad.replace(bad.find(line), line.size(), declared);
    {
      std::ofstream out(dir / "bad.rti", std::ios::binary);
      out << bad;
    }
    const e2e::CommandResult r = e2e::surrogate("render " + e2e::quote(dir / "bad.rti") + " --light 0,0,1 -o " +
                                                e2e::quote(dir / "x.png"));
    requireRefused(r, {"bad.rti", declared == "4 99 1\n" ? "basis type is 99" : "element size is 0"});
    CHECK_FALSE(fs::exists(dir / "x.png"));
    requireRefused(e2e::surrogate("info " + e2e::quote(dir / "bad.rti")), {"bad.rti"});
  }
}

// ---- Capture folders -------------------------------------------------------------------------

TEST_CASE("a file name that is not UTF-8 is refused at the scan, shown escaped, with what to do") {
  const fs::path capture = e2e::smallCapture(e2e::freshDir("inputs-latin1"));
  fs::rename(capture / "original-captures/IMG_0002.dng", capture / "original-captures/IMG_\xE9t\xE9.dng");
  const e2e::CommandResult r = e2e::surrogate("run " + e2e::quote(capture) + " --quiet");
  requireRefused(r, {"original-captures/IMG_\\xE9t\\xE9.dng", "not UTF-8", "rename"});
  CHECK_FALSE(fs::exists(capture / "assembly-files"));
  // Elsewhere in the capture too (a note in a sub-folder), and for info.
  fs::rename(capture / "original-captures/IMG_\xE9t\xE9.dng", capture / "original-captures/IMG_0002.dng");
  fs::create_directories(capture / "notes");
  std::ofstream(capture / "notes" / "caf\xE9.txt") << "notes";
  requireRefused(e2e::surrogate("run " + e2e::quote(capture) + " --quiet"), {"notes/caf\\xE9.txt", "rename"});
  requireRefused(e2e::surrogate("info " + e2e::quote(capture)), {"notes/caf\\xE9.txt"});
  // The capture folder's own name, which titles the project by default.
  fs::remove_all(capture / "notes");
  const fs::path renamed = capture.parent_path() / "caf\xE9";
  fs::rename(capture, renamed);
  requireRefused(e2e::surrogate("run " + e2e::quote(renamed) + " --quiet"), {"caf\\xE9", "capture folder's name", "rename"});
  CHECK_FALSE(fs::exists(renamed / "assembly-files"));
}

TEST_CASE("symbolic link loops are refused with a message, not a filesystem error") {
  const fs::path capture = e2e::smallCapture(e2e::freshDir("inputs-loops"));
  // A folder linking to itself inside the capture.
  fs::create_directories(capture / "notes");
  fs::create_directory_symlink("../notes", capture / "notes" / "loop");
  requireRefused(e2e::surrogate("run " + e2e::quote(capture) + " --quiet"), {"notes/loop", "symbolic link"});
  fs::remove(capture / "notes" / "loop");
  // Two links pointing at each other at the top of the capture.
  fs::create_symlink("b", capture / "a");
  fs::create_symlink("a", capture / "b");
  requireRefused(e2e::surrogate("run " + e2e::quote(capture) + " --quiet"), {"symbolic link"});
  fs::remove(capture / "a");
  fs::remove(capture / "b");
  // The capture folder itself a loop: every command that takes a capture.
  const fs::path dir = capture.parent_path();
  fs::create_symlink(dir / "loop2", dir / "loop1");
  fs::create_symlink(dir / "loop1", dir / "loop2");
  const std::string loop = e2e::quote(dir / "loop1");
  requireRefused(e2e::surrogate("run " + loop + " --quiet"), {"loop1", "loop of symbolic links"});
  requireRefused(e2e::surrogate("lights " + loop + " -o " + e2e::quote(dir / "x.lp") + " --quiet"), {"loop1"});
  requireRefused(e2e::surrogate("info " + loop), {"loop1", "loop of symbolic links"});
  requireRefused(e2e::surrogate("report " + loop + " -o " + e2e::quote(dir / "r.html")), {"loop1"});
  requireRefused(e2e::surrogate("pack " + loop + " -o " + e2e::quote(dir / "p.zip")), {"loop1"}, /*usage=*/true);
}
