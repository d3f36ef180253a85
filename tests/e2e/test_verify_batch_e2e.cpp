// verify --batch on packages a batch made: a flipped byte named with its package and file, and
// --sample drawing the packages the ledger has not verified, the same for a seed.
#include <catch2/catch.hpp>
#include <chrono>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <map>
#include <set>
#include <nlohmann/json.hpp>
#include <sstream>
#include <thread>

#include "batch_e2e_support.h"
#include "e2e_support.h"
#include "ledger_lines.h"

namespace fs = std::filesystem;
using e2e::quote;
using nlohmann::json;
using namespace batch_e2e;

TEST_CASE("verify --batch names the one package of a list whose byte was flipped and the file", "[batch]") {
  const fs::path dir = e2e::freshDir("batch-audit");
  const fs::path list = makeCaptures(dir, 3);
  REQUIRE(e2e::surrogate("batch " + quote(list) + " -o " + quote(dir / "made.jsonl") + " --do run,pack --no-report --quiet")
              .exitCode == 0);
  std::ofstream(dir / "packages.txt") << (dir / "cap1.zip").string() << "\n" << (dir / "cap2.zip").string() << "\n"
                                      << (dir / "cap3.zip").string() << "\n";
  {  // one byte in the middle of cap2.zip, inside an original's compressed bytes
    std::fstream f(dir / "cap2.zip", std::ios::in | std::ios::out | std::ios::binary);
    const std::streamoff middle = static_cast<std::streamoff>(fs::file_size(dir / "cap2.zip") / 2);
    f.seekg(middle);
    char c = 0;
    f.read(&c, 1);
    c = static_cast<char>(c ^ 0x5a);
    f.seekp(middle);
    f.write(&c, 1);
  }
  const fs::path audit = dir / "audit-2026.jsonl";
  const auto r = e2e::surrogate("verify --batch " + quote(dir / "packages.txt") + " -o " + quote(audit) + " --jobs 2");
  INFO(r.output);
  CHECK(r.exitCode == 3);
  CHECK(r.output.find("FAIL  " + (dir / "cap2.zip").string() + "  fixity failure") != std::string::npos);
  CHECK(r.output.find("3 package(s): 2 sound, 1 not") != std::string::npos);
  const std::vector<json> lines = ledgerLines(audit);
  REQUIRE(lines.size() == 3);
  for (const json& j : lines) {
    CHECK(j["step"] == "verify");
    if (j["package"] == (dir / "cap2.zip").string()) {  // a package, named so
      CHECK(j["exit"] == 3);
      // The damaged entry is named: the file to restore from another copy.
      CHECK(j["message"].get<std::string>().find("cap2/data/") != std::string::npos);
    } else {
      CHECK(j["exit"] == 0);
    }
  }
  // Run again: the sound ones stand, the damaged one is checked again (and fails again).
  const auto again = e2e::surrogate("verify --batch " + quote(dir / "packages.txt") + " -o " + quote(audit) + " --quiet");
  CHECK(again.exitCode == 3);
  CHECK(ledgerLines(audit).size() == 4);
}

TEST_CASE("verify --batch --sample draws packages the ledger has not verified and the same for a seed", "[batch]") {
  const fs::path dir = e2e::freshDir("batch-sample");
  const fs::path list = makeCaptures(dir, 3);
  REQUIRE(e2e::surrogate("batch " + quote(list) + " -o " + quote(dir / "made.jsonl") + " --do run,pack --no-report --quiet")
              .exitCode == 0);
  std::ofstream(dir / "packages.txt") << (dir / "cap1.zip").string() << "\n" << (dir / "cap2.zip").string() << "\n"
                                      << (dir / "cap3.zip").string() << "\n";
  const std::string command = "verify --batch " + quote(dir / "packages.txt") + " --sample 2 --seed 7 -o ";
  const auto a = e2e::surrogate(command + quote(dir / "a.jsonl"));
  const auto b = e2e::surrogate(command + quote(dir / "b.jsonl"));
  CHECK(a.exitCode == 0);
  CHECK(a.output.find("Sample of 2 package(s), drawn with seed 7 from the 3 of 3") != std::string::npos);
  const auto la = ledgerLines(dir / "a.jsonl"), lb = ledgerLines(dir / "b.jsonl");
  REQUIRE(la.size() == 2);
  REQUIRE(lb.size() == 2);
  std::set<std::string> drawn;
  for (std::size_t i = 0; i < 2; ++i) {
    drawn.insert(la[i]["package"].get<std::string>());
    bool same = false;
    for (const json& j : lb) same = same || j["package"] == la[i]["package"];
    CHECK(same);  // the same seed, the same draw
  }
  // The next run of the audit takes the one left.
  const auto next = e2e::surrogate(command + quote(dir / "a.jsonl"));
  CHECK(next.output.find("Sample of 1 package(s), drawn with seed 7 from the 1 of 3") != std::string::npos);
  const auto all = ledgerLines(dir / "a.jsonl");
  REQUIRE(all.size() == 3);
  CHECK(drawn.count(all[2]["package"].get<std::string>()) == 0);
}
