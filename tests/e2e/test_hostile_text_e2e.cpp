// The hostile-input suite, text from files: an EXIF make in Latin-1, a model holding a control
// character (JPEG and DNG), a prior .lp of random bytes, a manifest path with an escape sequence.
// Each is data: recorded escaped (\xHH) with its raw bytes where it is camera metadata, the
// carrier always valid, never exit 5, never a raw control byte on the terminal (core/text.h).
// The EXIF is written with Exiv2's own command-line tool (scripts/install-deps installs it).
#include <catch2/catch.hpp>

#include <fstream>
#include <random>
#include <string>

#include "carrier/carrier.h"
#include "e2e_support.h"

namespace fs = std::filesystem;
using namespace surrogate;
using namespace std::string_literals;

namespace {

// No byte of a control character but line breaks: what a terminal would obey.
bool hasRawControl(const std::string& text) {
  for (unsigned char c : text)
    if ((c < 0x20 && c != '\n' && c != '\r' && c != '\t') || c == 0x7F) return true;
  return false;
}

void setExif(const fs::path& file, const std::string& key, const std::string& bytes) {
  // exiv2 -M takes the value after the type; the bytes go through a file so the shell never
  // sees them.
  const fs::path commands = file.parent_path() / ".exiv2-commands";
  std::ofstream(commands, std::ios::binary) << "set " << key << " Ascii " << bytes << "\n";
  const e2e::CommandResult r = e2e::runShell("exiv2 -m " + e2e::quote(commands) + " " + e2e::quote(file));
  fs::remove(commands);
  INFO(r.output);
  REQUIRE(r.exitCode == 0);
}

const carrier::FileRecord& recordOf(const carrier::Carrier& c, const std::string& path) {
  const carrier::FileRecord* f = c.findFileByPath(path);
  REQUIRE(f != nullptr);
  return *f;
}

std::string cameraValue(const carrier::FileRecord& f, const std::string& name) {
  for (const auto& [k, v] : f.camera)
    if (k == name) return v;
  return "";
}

std::string rawHex(const carrier::FileRecord& f, const std::string& field) {
  for (const auto& [k, v] : f.cameraRaw)
    if (k == field) return v;
  return "";
}

}  // namespace

TEST_CASE("EXIF that is not UTF-8 or holds control characters is recorded escaped with its bytes") {
  const fs::path dir = e2e::freshDir("hostile-text-exif");
  const fs::path cap = e2e::smallCapture(dir, 8);
  // A JPEG export and a DNG original, one field each.
  setExif(cap / "jpeg-exports/IMG_0001.jpg", "Exif.Image.Make", "Can\xE9n");          // Latin-1
  setExif(cap / "original-captures/IMG_0002.dng", "Exif.Image.Model", "EOS\x01" "5D");  // SOH
  setExif(cap / "original-captures/IMG_0003.dng", "Exif.Image.Model", "EOS\x1B[31m");  // ESC
  const e2e::CommandResult run = e2e::surrogate("run " + e2e::quote(cap) + " --quiet --no-report");
  INFO(run.output);
  REQUIRE(run.exitCode == 0);
  CHECK_FALSE(hasRawControl(run.output));

  const carrier::Carrier c = carrier::loadCarrier(cap / "assembly-files/carrier.xml");  // validates
  const carrier::FileRecord& jpeg = recordOf(c, "jpeg-exports/IMG_0001.jpg");
  CHECK(cameraValue(jpeg, "make") == "Can\\xE9n");
  CHECK(rawHex(jpeg, "make") == "43616ee96e");  // C a n 0xE9 n
  const carrier::FileRecord& dng = recordOf(c, "original-captures/IMG_0002.dng");
  CHECK(cameraValue(dng, "model") == "EOS\\x015D");
  CHECK(rawHex(dng, "model") == "454f53013544");
  CHECK(cameraValue(recordOf(c, "original-captures/IMG_0003.dng"), "model") == "EOS\\x1B[31m");

  for (const std::string file : {"jpeg-exports/IMG_0001.jpg", "original-captures/IMG_0003.dng"}) {
    const e2e::CommandResult info = e2e::surrogate("info " + e2e::quote(cap / file));
    INFO(info.output);
    CHECK(info.exitCode == 0);
    CHECK_FALSE(hasRawControl(info.output));
    CHECK(info.output.find("\\x") != std::string::npos);
    const e2e::CommandResult json = e2e::surrogate("info " + e2e::quote(cap / file) + " --json");
    CHECK(json.exitCode == 0);
    CHECK(json.output.find('\xE9') == std::string::npos);  // JSON is UTF-8
  }
  const fs::path pkg = dir / "pkg.zip";
  REQUIRE(e2e::surrogate("pack " + e2e::quote(cap) + " -o " + e2e::quote(pkg) + " --quiet").exitCode == 0);
  const e2e::CommandResult verify = e2e::surrogate("verify " + e2e::quote(pkg) + " --reexecute --quiet");
  INFO(verify.output);
  CHECK(verify.exitCode == 0);
}

TEST_CASE("a prior .lp of random bytes or foreign names is prior work with an escaped warning") {
  const fs::path dir = e2e::freshDir("hostile-text-lp");
  const fs::path cap = e2e::smallCapture(dir, 8);
  fs::create_directories(cap / "assembly-files");
  std::mt19937 rng(7);
  std::string bytes(3000, '\0');
  for (char& b : bytes) b = static_cast<char>(rng() & 0xFF);
  std::ofstream(cap / "assembly-files/random.lp", std::ios::binary) << bytes;
  std::ofstream(cap / "assembly-files/latin1.lp", std::ios::binary)
      << "2\nIMG_\xE9\x01.jpg 0.1 0.2 0.97\nIMG_0002.jpg 0.2\0 0.1 0.97\n"s;  // a NUL too
  const e2e::CommandResult run = e2e::surrogate("run " + e2e::quote(cap) + " --quiet --no-report");
  INFO(run.output);
  REQUIRE(run.exitCode == 0);
  CHECK_FALSE(hasRawControl(run.output));
  const carrier::Carrier c = carrier::loadCarrier(cap / "assembly-files/carrier.xml");
  CHECK(recordOf(c, "assembly-files/random.lp").role == "prior");
  CHECK(recordOf(c, "assembly-files/latin1.lp").role == "prior");
  bool warned = false;
  for (const carrier::LogEntry& e : c.log) warned = warned || e.text.find("random.lp") != std::string::npos;
  CHECK(warned);
}

TEST_CASE("a manifest path with an escape sequence reaches the terminal escaped") {
  const fs::path dir = e2e::freshDir("hostile-text-manifest");
  const fs::path cap = e2e::smallCapture(dir, 8);
  REQUIRE(e2e::surrogate("run " + e2e::quote(cap) + " --quiet --no-report").exitCode == 0);
  const fs::path bag = dir / "bag";
  REQUIRE(e2e::surrogate("pack " + e2e::quote(cap) + " -o " + e2e::quote(bag) + " --quiet").exitCode == 0);
  // A hostile line in the manifest (the tag manifest no longer matches: a fixity failure).
  std::ofstream(bag / "manifest-sha256.txt", std::ios::app)
      << std::string(64, '0') << "  data/\x1B]0;owned\x07\x1B[2J.jpg\n";
  const e2e::CommandResult verify = e2e::surrogate("verify " + e2e::quote(bag));
  INFO(verify.output);
  CHECK(verify.exitCode == 3);
  CHECK_FALSE(hasRawControl(verify.output));
  CHECK(verify.output.find("\\x1B") != std::string::npos);
}

TEST_CASE("a NUL in an .lp is shown escaped in the whole message, not where it cut it") {
  const fs::path dir = e2e::freshDir("hostile-text-nul");
  std::ofstream(dir / "nul.lp", std::ios::binary) << "2\nIMG_0001.jpg 0.1 0.2 0.97\nIMG_0002.jpg 0.2\0x 0.1 0.97\n"s;
  for (const std::string& command : {"info " + e2e::quote(dir / "nul.lp"),
                                    "fit --lp " + e2e::quote(dir / "nul.lp") + " -o " + e2e::quote(dir / "m.ptm")}) {
    const e2e::CommandResult r = e2e::surrogate(command);
    INFO(r.output);
    CHECK(r.exitCode == 1);
    CHECK(r.output.find("\"0.2\\x00x\" is not a number") != std::string::npos);
    CHECK(r.output.find('\0') == std::string::npos);
  }
}
