// The BagIt writer: layout, manifests (digests recomputed with OpenSSL), escaping,
// Payload-Oxum, byte-identical archives, and no partial output on failure.
#include <catch2/catch.hpp>

#include <signal.h>
#include <sys/resource.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <atomic>
#include <cstdlib>
#include <fstream>
#include <random>

#include "archive/bag.h"
#include "bag_check.h"
#include "core/error.h"
#include "test_files.h"

namespace fs = std::filesystem;
using namespace surrogate;
using namespace surrogate::archive;

using testfiles::freshDir;
using testfiles::slurp;

namespace {

void writeBytes(const fs::path& p, const std::string& bytes) {
  fs::create_directories(p.parent_path());
  std::ofstream(p, std::ios::binary) << bytes;
}

std::string randomBytes(std::size_t n, unsigned seed) {
  std::mt19937 rng(seed);
  std::string s(n, '\0');
  for (char& c : s) c = static_cast<char>(rng() & 0xff);
  return s;
}

// A small set of sources: binary files, an empty file, awkward names.
BagInput sampleInput(const fs::path& src) {
  BagInput in;
  const std::vector<std::pair<std::string, std::string>> files = {
      {"original-captures/IMG_0001.dng", randomBytes(300000, 1)},
      {"original-captures/IMG_0002.dng", randomBytes(2 * 1024 * 1024 + 17, 2)},
      {"jpeg-exports/IMG 0001.jpg", randomBytes(5000, 3)},
      {"finished-files/empty.txt", ""},
      {"finished-files/100%.png", randomBytes(10, 4)},
      {"finished-files/line\nbreak.txt", "two\nlines\n"},
      {"finished-files/carriage\rreturn.txt", "cr"},
      {"finished-files/ünïcödé.txt", "utf-8 name"},
  };
  for (const auto& [rel, bytes] : files) {
    writeBytes(src / rel, bytes);
    in.payload.push_back({"data/" + rel, src / rel, ""});
  }
  in.info = {{"Source-Organization", "Museum of Tests"},
             {"External-Identifier", "INV-42"},
             {"Contact-Name", "Ana Silva"},
             {"External-Description", "first line\nsecond line"}};
  in.softwareAgent = "Surrogate test";
  in.tagFiles = [](const std::vector<PayloadDigest>& d) {
    return std::vector<TagFile>{{"metadata/count.txt", std::to_string(d.size()) + "\n"}};
  };
  return in;
}

struct EpochGuard {
  explicit EpochGuard(const char* value) {
    if (value) ::setenv("SOURCE_DATE_EPOCH", value, 1);
    else ::unsetenv("SOURCE_DATE_EPOCH");
  }
  ~EpochGuard() { ::unsetenv("SOURCE_DATE_EPOCH"); }
};

}  // namespace

TEST_CASE("a directory bag has the RFC 8493 layout and valid manifests", "[archive][bag]") {
  const fs::path dir = freshDir("layout");
  BagInput in = sampleInput(dir / "src");
  const BagResult r = writeBag(in, dir / "bag");
  CHECK(r.format == BagFormat::Directory);
  CHECK(r.payloadFiles == 8);

  const bagcheck::BagFiles bag = bagcheck::readBag(dir / "bag");
  const auto problems = bagcheck::validate(bag);
  INFO((problems.empty() ? std::string() : problems.front()));
  CHECK(problems.empty());
  for (const char* name : {"bagit.txt", "bag-info.txt", "manifest-sha256.txt", "manifest-sha512.txt",
                           "tagmanifest-sha256.txt", "tagmanifest-sha512.txt", "metadata/count.txt"})
    CHECK(bag.files.count(name) == 1);
  // Payload byte-identical to the sources.
  for (const PayloadSource& p : in.payload) CHECK(bag.files.at(p.bagPath) == slurp(p.source));
  // The tag manifest covers the caller's tag file, never itself.
  const std::string tag = bag.files.at("tagmanifest-sha256.txt");
  CHECK(tag.find("metadata/count.txt") != std::string::npos);
  CHECK(tag.find("tagmanifest") == std::string::npos);
  CHECK(bag.files.at("metadata/count.txt") == "8\n");
}

TEST_CASE("bag-info.txt has Payload-Oxum, Bag-Size, Bagging-Date, agent and the user's labels", "[archive][bag]") {
  EpochGuard epoch("1700000000");  // 2023-11-14T22:13:20Z
  const fs::path dir = freshDir("info");
  BagInput in = sampleInput(dir / "src");
  std::uint64_t bytes = 0;
  for (const PayloadSource& p : in.payload) bytes += fs::file_size(p.source);
  writeBag(in, dir / "bag");
  const auto info = bagcheck::parseBagInfo(slurp(dir / "bag" / "bag-info.txt"));
  CHECK(info.find("Payload-Oxum")->second == std::to_string(bytes) + ".8");
  CHECK(info.find("Bagging-Date")->second == "2023-11-14");
  CHECK(info.find("Bag-Software-Agent")->second == "Surrogate test");
  CHECK(info.find("Bag-Size")->second == humanSize(bytes));
  CHECK(info.find("Source-Organization")->second == "Museum of Tests");
  CHECK(info.find("External-Identifier")->second == "INV-42");
  CHECK(info.find("Contact-Name")->second == "Ana Silva");
  // A multi-line value is folded into a continuation line.
  CHECK(info.find("External-Description")->second == "first line\nsecond line");
  CHECK(slurp(dir / "bag" / "bag-info.txt").find("first line\n  second line\n") != std::string::npos);
}

TEST_CASE("manifest paths escape CR, LF and % as RFC 8493 says", "[archive][bag]") {
  CHECK(escapeManifestPath("data/a%b\nc\rd e") == "data/a%25b%0Ac%0Dd e");
  const fs::path dir = freshDir("escape");
  writeBag(sampleInput(dir / "src"), dir / "bag");
  const std::string manifest = slurp(dir / "bag" / "manifest-sha256.txt");
  CHECK(manifest.find("data/finished-files/line%0Abreak.txt") != std::string::npos);
  CHECK(manifest.find("data/finished-files/carriage%0Dreturn.txt") != std::string::npos);
  CHECK(manifest.find("data/finished-files/100%25.png") != std::string::npos);
  CHECK(manifest.find("data/jpeg-exports/IMG 0001.jpg") != std::string::npos);
  // One line per payload file: no raw line break inside a path.
  CHECK(std::count(manifest.begin(), manifest.end(), '\n') == 8);
}

TEST_CASE("tar and zip bags are valid, with one top folder and fixed owner, mode and time", "[archive][bag]") {
  EpochGuard epoch("1700000000");
  const fs::path dir = freshDir("formats");
  const BagInput in = sampleInput(dir / "src");
  for (const char* name : {"pkg.tar", "pkg.zip"}) {
    const BagResult r = writeBag(in, dir / name);
    CHECK(r.format == bagFormatFor(dir / name));
    const bagcheck::BagFiles bag = bagcheck::readBag(dir / name);
    CHECK(bag.top == "pkg");
    const auto problems = bagcheck::validate(bag);
    INFO(name << ": " << (problems.empty() ? std::string() : problems.front()));
    CHECK(problems.empty());
    CHECK(bag.files.at("data/original-captures/IMG_0002.dng") == slurp(dir / "src/original-captures/IMG_0002.dng"));
  }
  // Members in byte order of their names.
  for (const char* name : {"pkg.tar", "pkg.zip"}) {
    const auto order = bagcheck::readBag(dir / name).order;
    CHECK(std::is_sorted(order.begin(), order.end()));
    CHECK(order.front() == "bag-info.txt");
    CHECK(order.back() == "tagmanifest-sha512.txt");
  }
}

TEST_CASE("with SOURCE_DATE_EPOCH, two tar or zip packs of the same inputs are byte-identical", "[archive][bag]") {
  EpochGuard epoch("1700000000");
  const fs::path dir = freshDir("repro");
  const BagInput in = sampleInput(dir / "src");
  for (const char* ext : {".tar", ".zip"}) {
    fs::create_directories(dir / "a");
    fs::create_directories(dir / "b");
    writeBag(in, dir / "a" / (std::string("pkg") + ext));
    // Touch the sources: file times must not leak into the package.
    for (const PayloadSource& p : in.payload) fs::last_write_time(p.source, fs::file_time_type::clock::now());
    writeBag(in, dir / "b" / (std::string("pkg") + ext));
    CHECK(slurp(dir / "a" / (std::string("pkg") + ext)) == slurp(dir / "b" / (std::string("pkg") + ext)));
  }
}

TEST_CASE("a zip does not depend on the machine's time zone or locale", "[archive][bag]") {
  EpochGuard epoch("1700000000");
  const fs::path dir = freshDir("zone");
  const BagInput in = sampleInput(dir / "src");
  fs::create_directories(dir / "a");
  fs::create_directories(dir / "b");
  ::setenv("TZ", "America/New_York", 1);
  ::setenv("LC_ALL", "C", 1);
  writeBag(in, dir / "a/pkg.zip");
  writeBag(in, dir / "a/pkg.tar");
  ::setenv("TZ", "Asia/Tokyo", 1);
  ::setenv("LC_ALL", "C.UTF-8", 1);
  writeBag(in, dir / "b/pkg.zip");
  writeBag(in, dir / "b/pkg.tar");
  ::unsetenv("TZ");
  ::unsetenv("LC_ALL");
  CHECK(slurp(dir / "a/pkg.zip") == slurp(dir / "b/pkg.zip"));
  CHECK(slurp(dir / "a/pkg.tar") == slurp(dir / "b/pkg.tar"));
}

TEST_CASE("the payload is sorted and the order of the inputs does not matter", "[archive][bag]") {
  EpochGuard epoch("1700000000");
  const fs::path dir = freshDir("order");
  BagInput in = sampleInput(dir / "src");
  writeBag(in, dir / "a.tar");
  std::reverse(in.payload.begin(), in.payload.end());
  writeBag(in, dir / "b.tar");
  // Names differ (top folder a/ vs b/), so compare the manifests and the member order.
  CHECK(bagcheck::readBag(dir / "a.tar").files == bagcheck::readBag(dir / "b.tar").files);
  const std::string manifest = bagcheck::readBag(dir / "a.tar").files.at("manifest-sha256.txt");
  std::vector<std::string> paths;
  for (const auto& [hex, path] : bagcheck::parseManifest(manifest)) paths.push_back(path);
  CHECK(std::is_sorted(paths.begin(), paths.end()));
}

TEST_CASE("a missing input fails with its name and leaves no output", "[archive][bag][failure]") {
  const fs::path dir = freshDir("missing");
  BagInput in = sampleInput(dir / "src");
  fs::remove(dir / "src/jpeg-exports/IMG 0001.jpg");
  for (const char* name : {"bag", "bag.tar", "bag.zip"}) {
    try {
      writeBag(in, dir / name);
      FAIL("no error");
    } catch (const Error& e) {
      CHECK(e.kind() == ErrorKind::Input);
      CHECK(e.file().find("IMG 0001.jpg") != std::string::npos);
    }
  }
  // Nothing but the sources: no final name, no temporary leftovers.
  std::vector<std::string> left;
  for (const auto& entry : fs::directory_iterator(dir)) left.push_back(entry.path().filename().string());
  CHECK(left == std::vector<std::string>{"src"});
}

TEST_CASE("a file without read permission fails with its name and leaves no output", "[archive][bag][failure]") {
  if (::geteuid() == 0) return;  // root reads any file: the case cannot arise (tested above for missing files)
  const fs::path dir = freshDir("noread");
  BagInput in = sampleInput(dir / "src");
  fs::permissions(dir / "src/original-captures/IMG_0001.dng", fs::perms::none);
  try {
    writeBag(in, dir / "bag.tar");
    FAIL("no error");
  } catch (const Error& e) {
    CHECK(e.kind() == ErrorKind::Input);
    CHECK(e.file().find("IMG_0001.dng") != std::string::npos);
    CHECK(e.message().find("permission") != std::string::npos);
  }
  CHECK_FALSE(fs::exists(dir / "bag.tar"));
}

TEST_CASE("a symbolic link in the payload is refused, not followed", "[archive][bag][failure]") {
  const fs::path dir = freshDir("link");
  BagInput in = sampleInput(dir / "src");
  fs::create_symlink("/etc/passwd", dir / "src/finished-files/link.txt");
  in.payload.push_back({"data/finished-files/link.txt", dir / "src/finished-files/link.txt", ""});
  CHECK_THROWS_AS(writeBag(in, dir / "bag.tar"), Error);
  CHECK_FALSE(fs::exists(dir / "bag.tar"));
}

TEST_CASE("a file that changes while it is packed fails and leaves no output", "[archive][bag][failure]") {
  const fs::path dir = freshDir("changing");
  BagInput in = sampleInput(dir / "src");
  // When packing is under way, truncate a file that comes later (sorted order).
  bool truncated = false;
  in.progress = [&](std::uint64_t, std::uint64_t) {
    if (!truncated) {
      fs::resize_file(dir / "src/original-captures/IMG_0002.dng", 100);
      truncated = true;
    }
  };
  try {
    writeBag(in, dir / "bag.zip");
    FAIL("no error");
  } catch (const Error& e) {
    CHECK(e.kind() == ErrorKind::Input);
    CHECK(e.file().find("IMG_0002.dng") != std::string::npos);
    CHECK(e.message().find("changed size") != std::string::npos);
  }
  CHECK(std::distance(fs::directory_iterator(dir), fs::directory_iterator()) == 1);
}

TEST_CASE("a file whose digest differs from the recorded one raises PayloadChanged", "[archive][bag][failure]") {
  const fs::path dir = freshDir("expected");
  BagInput in = sampleInput(dir / "src");
  in.payload[0].expectedSha256 = std::string(64, '0');
  CHECK_THROWS_AS(writeBag(in, dir / "bag"), PayloadChanged);
  CHECK_FALSE(fs::exists(dir / "bag"));
  in.payload[0].expectedSha256 = bagcheck::sha256(slurp(in.payload[0].source));
  CHECK_NOTHROW(writeBag(in, dir / "bag"));
}

TEST_CASE("an output that cannot be written fails with its name and leaves nothing", "[archive][bag][failure]") {
  const fs::path dir = freshDir("unwritable");
  const BagInput in = sampleInput(dir / "src");
  SECTION("the folder does not exist") {
    try {
      writeBag(in, dir / "no/such/folder/bag.tar");
      FAIL("no error");
    } catch (const Error& e) {
      CHECK(e.file().find("bag.tar") != std::string::npos);
    }
  }
  SECTION("a read-only file system") {
    CHECK_THROWS_AS(writeBag(in, "/proc/surrogate-bag.tar"), Error);
    CHECK_FALSE(fs::exists("/proc/surrogate-bag.tar"));
  }
  SECTION("the disk fills up (a file-size limit stands in for a full disk)") {
    for (const char* name : {"bag", "bag.tar", "bag.zip"}) {
      struct rlimit old {};
      ::getrlimit(RLIMIT_FSIZE, &old);
      ::signal(SIGXFSZ, SIG_IGN);
      struct rlimit small = old;
      small.rlim_cur = 1024 * 1024;  // 1 MB: less than the payload
      ::setrlimit(RLIMIT_FSIZE, &small);
      bool threw = false;
      std::string file, message;
      try {
        writeBag(in, dir / name);
      } catch (const Error& e) {
        threw = true;
        file = e.file();
        message = e.message();
        CHECK(e.kind() == ErrorKind::Input);  // the environment's, not a bug: exit 1
      }
      ::setrlimit(RLIMIT_FSIZE, &old);
      CHECK(threw);
      CHECK(file.find(name) != std::string::npos);
      CHECK(message.find("ulimit -f") != std::string::npos);
      CHECK_FALSE(fs::exists(dir / name));
    }
    CHECK(std::distance(fs::directory_iterator(dir), fs::directory_iterator()) == 1);
  }
}

TEST_CASE("an existing non-empty folder is not overwritten", "[archive][bag][failure]") {
  const fs::path dir = freshDir("exists");
  const BagInput in = sampleInput(dir / "src");
  writeBytes(dir / "bag/keep.txt", "mine");
  CHECK_THROWS_AS(writeBag(in, dir / "bag"), Error);
  CHECK(slurp(dir / "bag/keep.txt") == "mine");
}

TEST_CASE("computed bag-info labels cannot be given as user metadata", "[archive][bag]") {
  const fs::path dir = freshDir("labels");
  BagInput in = sampleInput(dir / "src");
  in.info.push_back({"Payload-Oxum", "1.1"});
  CHECK_THROWS_AS(writeBag(in, dir / "bag"), Error);
  in.info.back() = {"Bad Label", "x"};
  CHECK_THROWS_AS(writeBag(in, dir / "bag"), Error);
  // The labels pack writes itself, in any case: given twice they would contradict each other.
  for (const char* own : {"Surrogate-Package-Identifier", "surrogate-packaging-time"}) {
    CHECK_THAT(bagInfoLabelProblem(own), Catch::Matchers::Contains("written by `surrogate pack` itself"));
    in.info.back() = {own, "urn:forged"};
    CHECK_THROWS_AS(writeBag(in, dir / "bag"), Error);
  }
  CHECK_FALSE(fs::exists(dir / "bag"));
  CHECK(bagInfoLabelProblem("Source-Organization").empty());
  // The packer's own labels go in through ownInfo, after the user's, once each.
  in.info.pop_back();
  in.ownInfo = {{"Surrogate-Package-Identifier", "urn:sha256:00"}, {"Surrogate-Packaging-Time", "2026-01-02T03:04:05Z"}};
  writeBag(in, dir / "bag");
  const std::string info = slurp(dir / "bag/bag-info.txt");
  CHECK(info.find("Surrogate-Package-Identifier: urn:sha256:00\n") != std::string::npos);
  CHECK(info.find("Surrogate-Package-Identifier") == info.rfind("Surrogate-Package-Identifier"));
  CHECK(info.find("External-Description") < info.find("Surrogate-Package-Identifier"));
}

TEST_CASE("a holder's bag-info labels come last, checked, a value on one line", "[archive][bag]") {
  const fs::path dir = freshDir("holder-labels");
  BagInput in = sampleInput(dir / "src");
  in.ownInfo = {{"Surrogate-Package-Identifier", "urn:sha256:00"}};
  in.holderInfo = {{"Contact-Name", "A. Archivist"}, {"External-Identifier", "INV-7"}, {"Contact-Name", "B. Archivist"}};
  writeBag(in, dir / "bag");
  const std::string info = slurp(dir / "bag/bag-info.txt");
  CHECK_THAT(info, Catch::Matchers::EndsWith("Surrogate-Package-Identifier: urn:sha256:00\nContact-Name: A. Archivist\n"
                                             "External-Identifier: INV-7\nContact-Name: B. Archivist\n"));
  for (const std::pair<std::string, std::string>& bad :
       std::vector<std::pair<std::string, std::string>>{{"Bag-Size", "1 KB"}, {"Contact Name", "x"},
                                                        {"Contact-Name", "one\ntwo"}, {"Contact-Name", "one\rtwo"}}) {
    in.holderInfo = {bad};
    INFO(bad.first << "=" << bad.second);
    CHECK_THROWS_AS(writeBag(in, dir / "refused"), Error);
    CHECK_FALSE(fs::exists(dir / "refused"));
  }
}

TEST_CASE("the partial output of a killed pack is removed by the next pack to the same name",
          "[archive][bag]") {
  const fs::path dir = freshDir("stale");
  // A process that has ended: its pid names the leftovers.
  const pid_t child = ::fork();
  if (child == 0) ::_exit(0);
  int status = 0;
  ::waitpid(child, &status, 0);
  const std::string dead = std::to_string(child);
  writeBytes(dir / (".bag.tar.part-" + dead + "-0"), "half a tar");
  writeBytes(dir / (".bag.tar.part-" + dead + "-7/data/x"), "a folder of one");
  fs::permissions(dir / (".bag.tar.part-" + dead + "-7/data"), fs::perms::owner_read | fs::perms::owner_exec);
  writeBytes(dir / ".bag.tar.part-1-0", "a pack still running (pid 1)");
  writeBytes(dir / (".other.tar.part-" + dead + "-0"), "another output's");
  writeBytes(dir / (".bag.tar.part-" + dead + "-x"), "not a name AtomicFile makes");
  const BagResult r = writeBag(sampleInput(dir / "src"), dir / "bag.tar");
  CHECK_FALSE(fs::exists(dir / (".bag.tar.part-" + dead + "-0")));
  CHECK_FALSE(fs::exists(dir / (".bag.tar.part-" + dead + "-7")));
  CHECK(fs::exists(dir / ".bag.tar.part-1-0"));
  CHECK(fs::exists(dir / (".other.tar.part-" + dead + "-0")));
  CHECK(fs::exists(dir / (".bag.tar.part-" + dead + "-x")));
  REQUIRE(r.removedLeftovers.size() == 2);
  CHECK_THAT(r.removedLeftovers[0], Catch::Matchers::Contains("process " + dead + " no longer runs"));
  CHECK(fs::exists(dir / "bag.tar"));
}

TEST_CASE("Bag-Size is human-readable", "[archive][bag]") {
  CHECK(humanSize(512) == "512 bytes");
  CHECK(humanSize(1500) == "1.5 KB");
  CHECK(humanSize(260000000000ULL) == "260.0 GB");
  CHECK(utcDate(1700000000) == "2023-11-14");
  CHECK(utcDateTime(1700000000) == "2023-11-14T22:13:20Z");
}
