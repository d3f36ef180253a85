// One ledger truth (issue 56), as a user meets it: a batch and its --summary agree after a
// failure and a retry, a list's relative paths mean the same from any working folder, a
// package's ledger entries say "package", and pack says that the failed step was an earlier
// run's and what this pack did about it.
#include <catch2/catch.hpp>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <regex>

#include "e2e_support.h"
#include "ledger_lines.h"

namespace fs = std::filesystem;
using e2e::quote;
using nlohmann::json;

namespace {

// A generated capture of 6 images at 200x150, `name` in `dir`.
fs::path generated(const fs::path& dir, const std::string& name) {
  const fs::path cap = dir / name;
  const auto r = e2e::runShell(std::string(GENERATOR_EXE) + " --out " + quote(cap) +
                               " --images 6 --width 200 --height 150 --sphere-radius 25 --seed 3");
  REQUIRE(r.exitCode == 0);
  fs::remove_all(cap / "truth");
  return cap;
}

std::size_t occurrences(const std::string& text, const std::string& part) {
  std::size_t n = 0;
  for (std::size_t at = text.find(part); at != std::string::npos; at = text.find(part, at + 1)) ++n;
  return n;
}

}  // namespace

TEST_CASE("after a failed pack and a retry that succeeds the batch and its summary both say done with exit 0",
          "[batch]") {
  const fs::path dir = e2e::freshDir("ledger-truth");
  const fs::path cap = generated(dir, "cap1");
  std::ofstream(dir / "list.txt") << cap.string() << "\n";
  const fs::path ledger = dir / "ledger.jsonl";
  const std::string batch = "batch " + quote(dir / "list.txt") + " -o " + quote(ledger) + " --no-report";
  const std::string summary = "batch --summary " + quote(ledger);
  REQUIRE(e2e::surrogate(batch).exitCode == 0);

  // The package is damaged (a byte flipped): the batch fails, and so does its summary.
  const fs::path package = dir / "cap1.zip";
  fs::copy_file(package, dir / "good.zip");
  {
    std::fstream f(package, std::ios::in | std::ios::out | std::ios::binary);
    f.seekp(2000);
    f.put('X');
  }
  const auto failed = e2e::surrogate(batch);
  INFO(failed.output);
  CHECK(failed.exitCode == 1);
  CHECK(e2e::surrogate(summary).exitCode == 1);

  // Restored from its copy and run again: the batch is done, and the summary agrees; the failure
  // stays in the ledger as history, and the package is not made twice.
  fs::copy_file(dir / "good.zip", package, fs::copy_options::overwrite_existing);
  const auto again = e2e::surrogate(batch);
  INFO(again.output);
  CHECK(again.exitCode == 0);
  CHECK(again.output.find("done  " + cap.string() + ":") != std::string::npos);
  const auto said = e2e::surrogate(summary);
  INFO(said.output);
  CHECK(said.exitCode == 0);
  CHECK(said.output.find("1 capture, 1 done, 0 failed") != std::string::npos);
  CHECK(said.output.find("  done  " + cap.string() + "; run ok; pack ok (after 1 failed attempt); verify ok") !=
        std::string::npos);
  const auto asJson = e2e::surrogate(summary + " --json");
  CHECK(asJson.exitCode == 0);
  const json s = json::parse(asJson.output);
  CHECK(s["done"] == 1);
  CHECK(s["failed"] == 0);
  REQUIRE(s["captures"].size() == 1);
  CHECK(s["captures"][0]["state"] == "done");
  CHECK(s["captures"][0]["packsMade"] == 1);
  CHECK(s["captures"][0]["steps"][1]["failedBefore"] == 1);
  std::size_t failedPacks = 0;
  for (const json& j : e2e::ledgerLines(ledger)) failedPacks += j["step"] == "pack" && j["exit"] != 0;
  CHECK(failedPacks == 1);
  CHECK(e2e::surrogate(batch).exitCode == 0);  // and stays done
  CHECK(e2e::surrogate(summary).exitCode == 0);
}

TEST_CASE("a list's relative paths are read from its folder whatever the working folder and the folder is said once",
          "[batch]") {
  const fs::path dir = e2e::freshDir("ledger-relative");
  generated(dir, "cap1");
  std::ofstream(dir / "list.txt") << "cap1\n";
  fs::create_directories(dir / "elsewhere");
  const std::string exe = SURROGATE_EXE;
  const auto fromElsewhere = e2e::runShell("cd " + quote(dir / "elsewhere") + " && " + exe +
                                           " batch ../list.txt -o ../ledger.jsonl --do run,pack --no-report");
  INFO(fromElsewhere.output);
  REQUIRE(fromElsewhere.exitCode == 0);
  CHECK(occurrences(fromElsewhere.output, "Relative paths in ../list.txt are read from its folder, " +
                                              dir.string() + ".") == 1);
  CHECK(fs::exists(dir / "cap1.zip"));
  CHECK_FALSE(fs::exists(dir / "elsewhere/cap1.zip"));
  const std::vector<json> lines = e2e::ledgerLines(dir / "ledger.jsonl");
  REQUIRE(lines.size() == 2);
  CHECK(lines[0]["capture"] == "cap1");  // the item as the list gives it
  // From the list's own folder, the same items by the same names: nothing left to do.
  const auto fromHome = e2e::runShell("cd " + quote(dir) + " && " + exe +
                                      " batch list.txt -o ledger.jsonl --do run,pack --no-report");
  INFO(fromHome.output);
  CHECK(fromHome.exitCode == 0);
  CHECK(fromHome.output.find("1 done (1 of them done before)") != std::string::npos);
  CHECK(e2e::ledgerLines(dir / "ledger.jsonl").size() == 2);
  // A list on standard input: the current folder, said so.
  const auto fromInput = e2e::runShell("cd " + quote(dir) + " && printf 'cap1\\n' | " + exe +
                                       " batch - -o other.jsonl --dry-run");
  INFO(fromInput.output);
  CHECK(fromInput.exitCode == 0);
  CHECK(fromInput.output.find("Relative paths in the list are read from the current folder, " + dir.string() + ".") !=
        std::string::npos);
}

TEST_CASE("verify --batch names each item of its ledger and of the summary a package not a capture", "[batch]") {
  const fs::path dir = e2e::freshDir("ledger-packages");
  const fs::path cap = generated(dir, "cap1");
  REQUIRE(e2e::surrogate("pack " + quote(cap) + " -o " + quote(dir / "cap1.zip") + " --quiet --no-report").exitCode == 0);
  std::ofstream(dir / "packages.txt") << "cap1.zip\n";
  const fs::path ledger = dir / "audit.jsonl";
  const auto audit = e2e::surrogate("verify --batch " + quote(dir / "packages.txt") + " -o " + quote(ledger));
  INFO(audit.output);
  REQUIRE(audit.exitCode == 0);
  const std::vector<json> lines = e2e::ledgerLines(ledger);
  REQUIRE(lines.size() == 1);
  CHECK(lines[0]["package"] == "cap1.zip");
  CHECK_FALSE(lines[0].contains("capture"));
  const auto said = e2e::surrogate("batch --summary " + quote(ledger));
  INFO(said.output);
  CHECK(said.exitCode == 0);
  CHECK(said.output.find("1 package, 1 done, 0 failed") != std::string::npos);
  CHECK(said.output.find("capture") == std::string::npos);
  const json s = json::parse(e2e::surrogate("batch --summary " + quote(ledger) + " --json").output);
  CHECK(s["captures"].empty());
  REQUIRE(s["packages"].size() == 1);
  CHECK(s["packages"][0]["package"] == "cap1.zip");
  CHECK_FALSE(s["packages"][0].contains("capture"));
  // Run again, the package is known by its line: verified before, unchanged since.
  const auto again = e2e::surrogate("verify --batch " + quote(dir / "packages.txt") + " -o " + quote(ledger));
  CHECK(again.exitCode == 0);
  CHECK(again.output.find("verified before, unchanged since") != std::string::npos);
}

TEST_CASE("pack says that the failed step was an earlier run's and that this processing completed", "[batch]") {
  const fs::path dir = e2e::freshDir("ledger-pack-words");
  const fs::path cap = e2e::processedCapture(dir);
  // The carrier of a run whose fit failed (as a run stopped at RtiFit leaves it).
  const fs::path carrier = cap / "assembly-files/carrier.xml";
  std::string xml = e2e::bytesOf(carrier);
  std::smatch m;
  REQUIRE(std::regex_search(xml, m, std::regex("<step id=\"(s[0-9]+)\" component=\"RtiFit\"")));
  const std::string id = m[1];
  const std::string done = "<result step=\"" + id + "\" status=\"completed\"";
  REQUIRE(xml.find(done) != std::string::npos);
  xml.replace(xml.find(done), done.size(), "<result step=\"" + id + "\" status=\"failed\"");
  std::ofstream(carrier, std::ios::binary | std::ios::trunc) << xml;
  const auto packed = e2e::surrogate("pack " + quote(cap) + " -o " + quote(dir / "cap.zip") + " --no-report");
  INFO(packed.output);
  REQUIRE(packed.exitCode == 0);
  CHECK(packed.output.find("Processed " + cap.string() + " before packing it, because an earlier run stopped at step " +
                           id + " (RtiFit), which failed; every step of this processing completed") != std::string::npos);
  CHECK(packed.output.find("first (step") == std::string::npos);
}
