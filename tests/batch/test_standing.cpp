// One ledger truth (issue 56): each step's last attempt decides, for --summary's standings and
// for what the batch finds done, so that the two agree after failures and retries; a package
// item's line names it "package", never "capture".
#include <unistd.h>

#include <catch2/catch.hpp>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>

#include "batch/ledger.h"
#include "batch/resume.h"
#include "batch/standing.h"

namespace fs = std::filesystem;
using namespace surrogate::batch;

namespace {

LedgerEntry attempt(const std::string& item, const std::string& step, int exit, const std::string& carrier = "") {
  LedgerEntry e;
  e.capture = item;
  e.step = step;
  e.exit = exit;
  e.carrierSha256 = carrier;
  return e;
}

}  // namespace

TEST_CASE("a step whose last attempt failed is not done even when an earlier success still matches the files") {
  const fs::path capture = fs::temp_directory_path() / ("standing-" + std::to_string(::getpid())) / "cap";
  fs::create_directories(capture / "assembly-files");
  std::ofstream(capture / "assembly-files/carrier.xml") << "abc";
  const std::string abc = "ba7816bf8f01cfea414140de5dae2223b00361a396177a9cb410ff61f20015ad";  // FIPS 180-2 B.1
  Ledger l;
  l.entries = {attempt(capture.string(), "run", 0, abc), attempt(capture.string(), "run", 3, abc)};
  std::string why;
  // The files are as the first run left them, but the last attempt failed: done again, as
  // --summary, which reads the last attempt, says the run failed.
  CHECK_FALSE(runStillValid(historyOf(l, capture.string(), "run"), carrierState(capture), why));
  CHECK(why == "its last run failed");
  CHECK(standings(l)[0].failed());
  l.entries.push_back(attempt(capture.string(), "run", 0, abc));
  CHECK(runStillValid(historyOf(l, capture.string(), "run"), carrierState(capture), why));
  CHECK_FALSE(standings(l)[0].failed());
  fs::remove_all(capture.parent_path());
}

TEST_CASE("standings count the failed attempts before a step's last success as history") {
  Ledger l;
  l.entries = {attempt("a", "run", 0), attempt("a", "pack", 1), attempt("a", "pack", 1), attempt("a", "pack", 0),
               attempt("a", "verify", 0), attempt("b", "run", 5), attempt("b", "run", 5)};
  const auto s = standings(l);
  REQUIRE(s.size() == 2);
  CHECK_FALSE(s[0].failed());
  CHECK(s[0].failuresBeforeSuccess("pack") == 2);
  CHECK(s[0].failuresBeforeSuccess("run") == 0);
  CHECK(s[0].failuresBeforeSuccess("verify") == 0);
  CHECK(s[1].failed());
  CHECK(s[1].failuresBeforeSuccess("run") == 0);  // its last attempt failed: the standing, not history
}

TEST_CASE("a package item is written as package without capture and read back as a package") {
  LedgerEntry e = attempt("packages/stela12.zip", "verify", 0);
  e.package = "/data/packages/stela12.zip";  // where the batch found it
  e.packageItem = true;
  const std::string line = ledgerLine(e);
  CHECK(line.rfind("{\"package\":\"packages/stela12.zip\",", 0) == 0);
  const nlohmann::json j = nlohmann::json::parse(line);
  CHECK_FALSE(j.contains("capture"));
  CHECK(j["package"] == "packages/stela12.zip");
  CHECK(j["step"] == "verify");
  LedgerEntry back;
  REQUIRE(parseLedgerLine(line, back));
  CHECK(back.packageItem);
  CHECK(back.capture == "packages/stela12.zip");
  // A capture's line keeps its capture and package apart.
  LedgerEntry pack = attempt("stela12", "pack", 0);
  pack.package = "stela12.zip";
  REQUIRE(parseLedgerLine(ledgerLine(pack), back));
  CHECK_FALSE(back.packageItem);
  CHECK(back.capture == "stela12");
  // A ledger written before: a verification whose capture is its package is a package item.
  REQUIRE(parseLedgerLine(R"({"capture":"p.zip","step":"verify","exit":0,"package":"p.zip"})", back));
  CHECK(back.packageItem);
  Ledger l;
  l.entries = {back};
  CHECK(standings(l)[0].isPackage);
  // Neither a capture nor a package: not a ledger line.
  CHECK_FALSE(parseLedgerLine(R"({"step":"verify","exit":0})", back));
}

TEST_CASE("a ledger whose first line is a package item is a ledger to append to") {
  const fs::path dir = fs::temp_directory_path() / ("standing-target-" + std::to_string(::getpid()));
  fs::remove_all(dir);
  fs::create_directories(dir);
  LedgerEntry e = attempt("p.zip", "verify", 0);
  e.packageItem = true;
  appendToLedger(dir / "audit.jsonl", e);
  CHECK_NOTHROW(checkLedgerTarget(dir / "audit.jsonl", dir / "list.txt"));
  std::ofstream(dir / "torn.jsonl") << ledgerLine(e).substr(0, 20);  // a writer's torn first line
  CHECK_NOTHROW(checkLedgerTarget(dir / "torn.jsonl", dir / "list.txt"));
  const Ledger back = readLedger(dir / "audit.jsonl");
  REQUIRE(back.entries.size() == 1);
  CHECK(back.entries[0].packageItem);
  fs::remove_all(dir);
}
