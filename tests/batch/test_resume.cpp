// What a batch finds done and still valid: keyed on the SHA-256 of the carrier and the package
// (values checked against FIPS 180-2's published example), the package read again only when its
// size or time changed.
#include <unistd.h>

#include <catch2/catch.hpp>
#include <filesystem>
#include <fstream>
#include <set>

#include "batch/resume.h"

namespace fs = std::filesystem;
using namespace surrogate::batch;

namespace {
// FIPS 180-2, appendix B.1: SHA-256("abc").
const std::string kAbc = "ba7816bf8f01cfea414140de5dae2223b00361a396177a9cb410ff61f20015ad";

fs::path freshFolder(const std::string& name) {
  const fs::path dir = fs::temp_directory_path() / ("resume-" + name + "-" + std::to_string(::getpid()));
  fs::remove_all(dir);
  fs::create_directories(dir);
  return dir;
}

void write(const fs::path& p, const std::string& text) {
  fs::create_directories(p.parent_path());
  std::ofstream(p, std::ios::binary) << text;
}

LedgerEntry done(const std::string& item, const std::string& step, const std::string& carrier,
                 const FileState& package) {
  LedgerEntry e;
  e.capture = item;
  e.step = step;
  e.carrierSha256 = carrier;
  e.packageSha256 = package.sha256;
  e.packageSize = package.size;
  e.packageMtimeNs = package.mtimeNs;
  return e;
}
}  // namespace

TEST_CASE("a run is done while the carrier is the one it left") {
  const fs::path capture = freshFolder("run") / "cap";
  Ledger ledger;
  std::string why;
  CHECK_FALSE(runStillValid(historyOf(ledger, capture.string(), "run"), carrierState(capture), why));
  CHECK(why == "no run recorded");
  write(capture / "assembly-files/carrier.xml", "abc");
  const FileState carrier = carrierState(capture);
  CHECK(carrier.sha256 == kAbc);
  LedgerEntry failed = done(capture.string(), "run", "", {});
  failed.exit = 5;
  ledger.entries.push_back(failed);
  CHECK_FALSE(runStillValid(historyOf(ledger, capture.string(), "run"), carrier, why));
  CHECK(why == "its last run failed");
  ledger.entries.push_back(done(capture.string(), "run", kAbc, {}));
  CHECK(runStillValid(historyOf(ledger, capture.string(), "run"), carrier, why));
  CHECK(historyOf(ledger, capture.string(), "run").nextAttempt() == 3);
  write(capture / "assembly-files/carrier.xml", "abd");  // the capture was run again since
  CHECK_FALSE(runStillValid(historyOf(ledger, capture.string(), "run"), carrierState(capture), why));
  CHECK(why == "the carrier changed since the run");
}

TEST_CASE("a pack is done while both the carrier and the package are as it left them") {
  const fs::path dir = freshFolder("pack");
  write(dir / "cap/assembly-files/carrier.xml", "abc");
  write(dir / "cap.zip", "a package");
  const FileState package = packageState(dir / "cap.zip");
  Ledger ledger;
  ledger.entries.push_back(done("cap", "pack", kAbc, package));
  std::string why;
  CHECK(packStillValid(historyOf(ledger, "cap", "pack"), carrierState(dir / "cap"), package, why));
  write(dir / "cap.zip", "another package!");
  CHECK_FALSE(packStillValid(historyOf(ledger, "cap", "pack"), carrierState(dir / "cap"),
                             packageState(dir / "cap.zip"), why));
  CHECK(why == "the package changed since the pack");
  fs::remove(dir / "cap.zip");
  CHECK_FALSE(packStillValid(historyOf(ledger, "cap", "pack"), carrierState(dir / "cap"),
                             packageState(dir / "cap.zip"), why));
  CHECK(why == "the package is gone since the pack");
}

TEST_CASE("a package whose size and time the ledger knows is not read again but a changed one is") {
  const fs::path dir = freshFolder("known");
  write(dir / "p.zip", "abc");
  FileState now = packageState(dir / "p.zip");
  CHECK(now.sha256 == kAbc);
  CHECK(now.size == 3);
  LedgerEntry known = done("p.zip", "verify", "", now);
  known.packageSha256 = std::string(64, '0');  // what the ledger says, trusted on size and time
  CHECK(packageState(dir / "p.zip", &known).sha256 == std::string(64, '0'));
  write(dir / "p.zip", "abcd");
  CHECK(packageState(dir / "p.zip", &known).sha256 != std::string(64, '0'));
  // A folder package: its tag manifest stands for it.
  write(dir / "bag/bagit.txt", "BagIt-Version: 1.0\n");
  write(dir / "bag/tagmanifest-sha256.txt", "abc");
  CHECK(packageState(dir / "bag").sha256 == kAbc);
}

TEST_CASE("a verification is done while the package is the one verified and re-executed when asked") {
  const fs::path dir = freshFolder("verify");
  write(dir / "p.zip", "abc");
  const FileState package = packageState(dir / "p.zip");
  Ledger ledger;
  ledger.entries.push_back(done("p.zip", "verify", "", package));
  std::string why;
  CHECK(verifyStillValid(historyOf(ledger, "p.zip", "verify"), package, false, why));
  CHECK_FALSE(verifyStillValid(historyOf(ledger, "p.zip", "verify"), package, true, why));
  CHECK(why == "no re-execution recorded as sound");
  ledger.entries.back().reexecuted = true;
  CHECK(verifyStillValid(historyOf(ledger, "p.zip", "verify"), package, true, why));
  LedgerEntry fixity = done("p.zip", "verify", "", package);
  fixity.exit = 3;
  Ledger failedOnly;
  failedOnly.entries.push_back(fixity);
  CHECK_FALSE(verifyStillValid(historyOf(failedOnly, "p.zip", "verify"), package, false, why));
}

TEST_CASE("a sample draws the count asked of distinct items the same for the same seed and all when fewer") {
  const auto a = drawSample(1000, 10, 42), b = drawSample(1000, 10, 42), c = drawSample(1000, 10, 43);
  REQUIRE(a.size() == 10);
  CHECK(a == b);
  CHECK(a != c);
  CHECK(std::set<std::size_t>(a.begin(), a.end()).size() == 10);
  CHECK(std::is_sorted(a.begin(), a.end()));
  CHECK(a.back() < 1000);
  CHECK(drawSample(3, 10, 1) == std::vector<std::size_t>{0, 1, 2});
  // Every item is drawn about equally often over many seeds (no item left out by a bias).
  std::vector<int> hits(20, 0);
  for (std::uint64_t seed = 0; seed < 2000; ++seed)
    for (std::size_t k : drawSample(20, 5, seed)) ++hits[k];
  for (int h : hits) CHECK((h > 380 && h < 620));  // 500 expected
}

TEST_CASE("a sampled audit draws from the packages not yet verified in the ledger") {
  Ledger ledger;
  LedgerEntry e;
  e.capture = "b.zip";
  e.step = "verify";
  ledger.entries.push_back(e);
  e.capture = "c.zip";
  e.exit = 3;  // failed: still to verify
  ledger.entries.push_back(e);
  CHECK(notYetVerified({"a.zip", "b.zip", "c.zip"}, ledger, false) == std::vector<std::size_t>{0, 2});
  CHECK(notYetVerified({"a.zip", "b.zip", "c.zip"}, ledger, true) == std::vector<std::size_t>{0, 1, 2});
}
