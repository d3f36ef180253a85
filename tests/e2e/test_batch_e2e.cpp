// surrogate batch and verify --batch, run as a user runs them, on small generated captures.
// The ledger is read with nlohmann's JSON, not with the batch's own reader; packages are
// checked by their bytes (SHA-256) and by `surrogate verify`.
#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

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

#include "core/digest.h"
#include "e2e_support.h"
#include "ledger_lines.h"

namespace fs = std::filesystem;
using e2e::quote;
using nlohmann::json;

namespace {

// `count` captures of 6 images at 200x150 in `dir` (cap1, cap2, ...), and the list naming them.
fs::path makeCaptures(const fs::path& dir, int count, int images = 6, int width = 200, int height = 150) {
  std::string list;
  for (int i = 1; i <= count; ++i) {
    const fs::path cap = dir / ("cap" + std::to_string(i));
    const auto r = e2e::runShell(std::string(GENERATOR_EXE) + " --out " + quote(cap) + " --images " +
                                 std::to_string(images) + " --width " + std::to_string(width) + " --height " +
                                 std::to_string(height) + " --sphere-radius " + std::to_string(height / 6) +
                                 " --seed " + std::to_string(i));
    REQUIRE(r.exitCode == 0);
    fs::remove_all(cap / "truth");
    list += cap.string() + "\n";
  }
  std::ofstream(dir / "list.txt") << "# generated captures\n" << list;
  return dir / "list.txt";
}

using e2e::ledgerLines;

std::size_t count(const std::vector<json>& lines, const std::string& capture, const std::string& step, int exit) {
  std::size_t n = 0;
  for (const json& j : lines)
    n += j["capture"] == capture && j["step"] == step && j["exit"] == exit;
  return n;
}

std::string sha(const fs::path& p) { return surrogate::digestFile(p).sha256; }

std::string version() {
  std::string v = e2e::surrogate("--version").output;  // "surrogate 0.1.0\n" and the libraries
  v = v.substr(0, v.find('\n'));
  return v.substr(v.find(' ') + 1);
}

// Processes whose command line names `text` (the jobs of a batch in a test's own folder).
std::vector<int> processesNaming(const std::string& text) {
  std::vector<int> out;
  for (const auto& entry : fs::directory_iterator("/proc")) {
    const std::string name = entry.path().filename().string();
    if (name.find_first_not_of("0123456789") != std::string::npos) continue;
    std::ifstream f(entry.path() / "cmdline", std::ios::binary);
    std::string cmdline((std::istreambuf_iterator<char>(f)), std::istreambuf_iterator<char>());
    if (cmdline.find(text) != std::string::npos && std::stoi(name) != ::getpid()) out.push_back(std::stoi(name));
  }
  return out;
}

}  // namespace

TEST_CASE("batch runs packs and verifies every capture of a list and run again does nothing", "[batch]") {
  const fs::path dir = e2e::freshDir("batch");
  const fs::path list = makeCaptures(dir, 3);
  const fs::path ledger = dir / "ledger.jsonl";
  const std::string command = "batch " + quote(list) + " -o " + quote(ledger) + " --jobs 2 --no-report";
  const auto first = e2e::surrogate(command);
  INFO(first.output);
  REQUIRE(first.exitCode == 0);
  const std::vector<json> lines = ledgerLines(ledger);
  REQUIRE(lines.size() == 9);  // 3 captures x run, pack, verify
  const std::string v = version();
  std::map<std::string, std::string> packages;
  for (const json& j : lines) {
    CHECK(j["exit"] == 0);
    CHECK(j["attempt"] == 1);
    CHECK(j["version"] == v);
    CHECK(j["peakMemory"].get<std::uint64_t>() > (1u << 20));
    CHECK(j["peakMemory"].get<std::uint64_t>() < (1ull << 30));
    CHECK(j["start"].get<std::string>() <= j["end"].get<std::string>());
    if (j["step"] == "pack") {
      const fs::path cap = j["capture"].get<std::string>();
      CHECK(j["package"] == (cap.parent_path() / (cap.filename().string() + ".zip")).string());
      CHECK(j["packageId"] == "urn:sha256:" + j["carrierSha256"].get<std::string>());
      CHECK(j["packageSha256"] == sha(j["package"].get<std::string>()));
      packages[j["capture"]] = j["packageSha256"];
    }
    if (j["step"] == "run") CHECK(j["carrierSha256"] == sha(fs::path(j["capture"].get<std::string>()) / "assembly-files/carrier.xml"));
  }
  REQUIRE(packages.size() == 3);
  for (const auto& [capture, digest] : packages) {
    const auto verified = e2e::surrogate("verify " + quote(capture + ".zip") + " --quiet");
    CHECK(verified.exitCode == 0);
  }
  // The per-job lines and the closing line.
  CHECK(first.output.find("done  " + (dir / "cap2").string() + ": run") != std::string::npos);
  CHECK(first.output.find("Batch of 3: 3 done") != std::string::npos);

  const auto dry = e2e::surrogate(command + " --dry-run");
  CHECK(dry.exitCode == 0);
  CHECK(dry.output.find((dir / "cap1").string() + ": run done (skipped); pack done (skipped); verify done (skipped)") !=
        std::string::npos);

  const auto again = e2e::surrogate(command);
  INFO(again.output);
  CHECK(again.exitCode == 0);
  CHECK(again.output.find("3 done (3 of them done before)") != std::string::npos);
  CHECK(ledgerLines(ledger).size() == 9);  // nothing ran, nothing recorded
  for (const auto& [capture, digest] : packages) CHECK(sha(capture + ".zip") == digest);

  // A capture run again since: the dry run says so, and the batch runs, packs and verifies it
  // only, replacing its own earlier package.
  REQUIRE(e2e::surrogate("run " + quote(dir / "cap2") + " --quiet --no-report").exitCode == 0);
  const auto dry2 = e2e::surrogate(command + " --dry-run");
  CHECK(dry2.output.find((dir / "cap2").string() + ": run (the carrier changed since the run); pack into " +
                         (dir / "cap2.zip").string() + " (after run)") != std::string::npos);
  const auto dryJson = e2e::surrogate(command + " --dry-run --json");
  INFO(dryJson.output);
  REQUIRE(dryJson.exitCode == 0);
  const json plan = json::parse(dryJson.output);
  CHECK(plan["dryRun"] == true);
  REQUIRE(plan["items"].size() == 3);
  CHECK(plan["items"][0]["capture"] == (dir / "cap1").string());
  CHECK(plan["items"][0]["steps"][1]["skipped"] == true);
  const json& cap2 = plan["items"][1];
  CHECK(cap2["capture"] == (dir / "cap2").string());
  REQUIRE(cap2["steps"].size() == 3);
  CHECK(cap2["steps"][0]["step"] == "run");
  CHECK(cap2["steps"][0]["skipped"] == false);
  CHECK(cap2["steps"][0]["why"] == "the carrier changed since the run");
  CHECK(cap2["steps"][1]["package"] == (dir / "cap2.zip").string());
  CHECK(cap2["steps"][2]["why"] == "after pack");
  REQUIRE(e2e::surrogate(command).exitCode == 0);
  const std::vector<json> after = ledgerLines(ledger);
  CHECK(after.size() == 12);
  CHECK(count(after, (dir / "cap2").string(), "pack", 0) == 2);
  CHECK(sha(dir / "cap1.zip") == packages[(dir / "cap1").string()]);
  CHECK(sha(dir / "cap2.zip") != packages[(dir / "cap2").string()]);

  // The summary merges the lines: every capture once, done.
  const auto summary = e2e::surrogate("batch --summary -o " + quote(ledger) + " --json");
  CHECK(summary.exitCode == 0);
  const json s = json::parse(summary.output);
  CHECK(s["items"] == 3);
  CHECK(s["done"] == 3);
  CHECK(s["failed"] == 0);
  const auto plain = e2e::surrogate("batch --summary " + quote(ledger));  // the ledger alone
  CHECK(plain.exitCode == 0);
  CHECK(plain.output.find("3 captures, 3 done, 0 failed (12 lines)") != std::string::npos);
}

TEST_CASE("a batch killed with kill -9 midway and run again finishes the rest and packs nothing twice", "[batch]") {
  const fs::path dir = e2e::freshDir("batch-kill");
  const fs::path list = makeCaptures(dir, 4);
  const fs::path ledger = dir / "ledger.jsonl";
  const std::vector<std::string> args = {"batch", list.string(), "-o", ledger.string(), "--no-report", "--quiet"};
  const pid_t pid = e2e::startSurrogate(args, "/dev/null");
  // Killed once the first capture is packed, the second being processed.
  const auto deadline = std::chrono::steady_clock::now() + std::chrono::minutes(3);
  bool packed = false;
  while (!packed && std::chrono::steady_clock::now() < deadline) {
    std::this_thread::sleep_for(std::chrono::milliseconds(20));
    std::ifstream in(ledger);
    std::string line;
    while (std::getline(in, line)) packed = packed || (line.find("\"step\":\"pack\"") != std::string::npos &&
                                                       line.find("\"exit\":0") != std::string::npos);
  }
  REQUIRE(packed);
  REQUIRE(::kill(pid, SIGKILL) == 0);
  int status = 0;
  REQUIRE(::waitpid(pid, &status, 0) == pid);
  REQUIRE(WIFSIGNALED(status));
  // Its jobs end with it (none is left holding a capture's lock).
  for (int i = 0; i < 100 && !processesNaming(dir.string()).empty(); ++i)
    std::this_thread::sleep_for(std::chrono::milliseconds(50));
  CHECK(processesNaming(dir.string()).empty());
  const std::vector<json> before = ledgerLines(ledger);
  REQUIRE(before.size() < 12);
  const std::string firstPackage = sha(dir / "cap1.zip");

  const auto rerun = e2e::surrogate("batch " + quote(list) + " -o " + quote(ledger) + " --no-report");
  INFO(rerun.output);
  REQUIRE(rerun.exitCode == 0);
  const std::vector<json> after = ledgerLines(ledger);
  for (int i = 1; i <= 4; ++i) {
    const std::string cap = (dir / ("cap" + std::to_string(i))).string();
    CHECK(count(after, cap, "pack", 0) == 1);  // packed once, never again
    CHECK(count(after, cap, "verify", 0) == 1);
    CHECK(fs::exists(cap + ".zip"));
  }
  CHECK(sha(dir / "cap1.zip") == firstPackage);
  // The lines before the kill are kept as they were.
  for (std::size_t i = 0; i < before.size(); ++i) CHECK(after[i] == before[i]);
  CHECK(e2e::surrogate("batch --summary -o " + quote(ledger)).exitCode == 0);
}

TEST_CASE("two batches on the same list at once process pack and verify each capture once and both succeed", "[batch]") {
  // A user starting the batch again while the first still runs, or two Slurm tasks on the same
  // item: the second finds each capture claimed or done, waits, and takes up what the first
  // has done (it used to fail on the capture's lock, and could run a capture again in the
  // moment between a step's end and its ledger line).
  const fs::path dir = e2e::freshDir("batch-twice");
  const fs::path list = makeCaptures(dir, 4);
  const fs::path ledger = dir / "ledger.jsonl";
  const std::string command =
      std::string(SURROGATE_EXE) + " batch " + quote(list) + " -o " + quote(ledger) + " --no-report --threads 1";
  for (const char* stagger : {"0", "0.3"}) {
    fs::remove(ledger);
    for (int i = 1; i <= 4; ++i) {
      const fs::path cap = dir / ("cap" + std::to_string(i));
      for (const char* made : {"assembly-files", "finished-files", ".surrogate"}) fs::remove_all(cap / made);
      fs::remove(dir / ("cap" + std::to_string(i) + ".zip"));
    }
    INFO("second batch " << stagger << " s after the first");
    const auto both = e2e::runShell("(" + command + " > " + quote(dir / "a.out") + " 2>&1; echo $? > " + quote(dir / "a.exit") +
                                    ") & (sleep " + stagger + "; " + command + " > " + quote(dir / "b.out") +
                                    " 2>&1; echo $? > " + quote(dir / "b.exit") + "); wait");
    INFO(e2e::bytesOf(dir / "a.out") << e2e::bytesOf(dir / "b.out"));
    CHECK(e2e::bytesOf(dir / "a.exit") == "0\n");
    CHECK(e2e::bytesOf(dir / "b.exit") == "0\n");
    const std::vector<json> lines = ledgerLines(ledger);
    for (int i = 1; i <= 4; ++i) {
      const std::string cap = (dir / ("cap" + std::to_string(i))).string();
      INFO(cap);
      CHECK(count(lines, cap, "run", 0) == 1);
      CHECK(count(lines, cap, "pack", 0) == 1);
      CHECK(count(lines, cap, "verify", 0) == 1);
      // The capture's own history: one run.
      const auto info = e2e::surrogate("info " + quote(cap) + " --json");
      REQUIRE(info.exitCode == 0);
      CHECK(json::parse(info.output)["carrier"]["runs"].size() == 1);
    }
    for (const json& j : lines) CHECK(j["exit"] == 0);
  }
}

TEST_CASE("a capture another command holds is waited for and then processed, not failed", "[batch]") {
  const fs::path dir = e2e::freshDir("batch-busy");
  const fs::path list = makeCaptures(dir, 2);
  const fs::path ledger = dir / "ledger.jsonl";
  // The capture's lock held for 2 s by another process, as a review's Apply or a run typed by
  // hand holds it (util-linux flock on the same file, same kind of lock).
  fs::create_directories(dir / "cap1" / ".surrogate");
  const auto started = std::chrono::steady_clock::now();
  // The batch starts once the holder has the lock (it leaves a mark then), however slow the
  // machine is to start it.
  const fs::path held = dir / "held";
  const auto r = e2e::runShell("(flock -x " + quote(dir / "cap1" / ".surrogate" / "lock") +
                               " sh -c 'touch \"$1\"; sleep 2' sh " + quote(held) + " &); while [ ! -e " + quote(held) +
                               " ]; do sleep 0.05; done; " + SURROGATE_EXE + " batch " + quote(list) + " -o " +
                               quote(ledger) + " --no-report");
  const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - started).count();
  INFO(r.output);
  CHECK(r.exitCode == 0);
  CHECK(seconds > 1.9);
  CHECK(r.output.find("wait  " + (dir / "cap1").string() + ": another Surrogate command is working on this capture") !=
        std::string::npos);
  CHECK(r.output.find("then run this command again") == std::string::npos);  // advice for a person, not here
  const std::vector<json> lines = ledgerLines(ledger);
  CHECK(lines.size() == 6);  // no line for the refused start
  for (const json& j : lines) CHECK(j["exit"] == 0);
  CHECK(count(lines, (dir / "cap1").string(), "pack", 0) == 1);
}

TEST_CASE("batch with --package-format tar packs each capture into NAME.tar that tar lists and verify passes", "[batch]") {
  const fs::path dir = e2e::freshDir("batch-tar");
  const fs::path list = makeCaptures(dir, 2);
  fs::create_directories(dir / "packages");
  const std::string command = "batch " + quote(list) + " -o " + quote(dir / "ledger.jsonl") + " --packages " +
                              quote(dir / "packages") + " --package-format tar --no-report --quiet";
  const auto first = e2e::surrogate(command);
  INFO(first.output);
  REQUIRE(first.exitCode == 0);
  CHECK(first.output == "Batch of 2: 2 done (0 of them done before), 0 failed; ledger " + (dir / "ledger.jsonl").string() +
                            "\n");  // --quiet: its one line
  for (const char* name : {"cap1", "cap2"}) {
    const fs::path tar = dir / "packages" / (std::string(name) + ".tar");
    INFO(tar);
    REQUIRE(fs::is_regular_file(tar));
    CHECK(!fs::exists(dir / "packages" / (std::string(name) + ".zip")));
    // GNU tar reads it: the bag's declaration and the carrier inside.
    const auto listed = e2e::runShell("tar -tf " + quote(tar));
    CHECK(listed.exitCode == 0);
    CHECK(listed.output.find("bagit.txt") != std::string::npos);
    CHECK(listed.output.find("data/assembly-files/carrier.xml") != std::string::npos);
    CHECK(count(ledgerLines(dir / "ledger.jsonl"), (dir / name).string(), "verify", 0) == 1);
  }
  const auto again = e2e::surrogate(command);
  CHECK(again.exitCode == 0);
  CHECK(again.output.find("2 done (2 of them done before)") != std::string::npos);
  const auto wrong = e2e::surrogate("batch " + quote(list) + " -o " + quote(dir / "ledger.jsonl") + " --package-format 7z");
  CHECK(wrong.exitCode == 2);
  CHECK(wrong.output.find("give zip or tar") != std::string::npos);
  // A packages folder inside a capture is refused before any job starts, as pack refuses its
  // -o there (a package in a capture would be bagged into its next package).
  for (const fs::path& inside : {dir / "cap1" / "original-captures", dir / "cap2", dir / "cap2" / "finished-files"}) {
    INFO(inside);
    const auto refused = e2e::surrogate("batch " + quote(list) + " -o " + quote(dir / "refused.jsonl") + " --packages " +
                                        quote(inside) + " --no-report");
    CHECK(refused.exitCode == 1);  // the exit of pack's refusal of its -o
    CHECK(refused.output.find("--packages " + inside.string()) != std::string::npos);
    CHECK(!fs::exists(dir / "refused.jsonl"));
  }
  CHECK(!fs::exists(dir / "cap1" / "original-captures" / "cap1.tar"));
}

TEST_CASE("a capture folder that does not exist fails at once and is not waited for as a busy capture", "[batch]") {
  // The lock's refusal of a missing folder named the step the refusal of a held capture names,
  // and the batch waited for it as for a busy capture, for 30 minutes.
  const fs::path dir = e2e::freshDir("batch-missing");
  const fs::path list = makeCaptures(dir, 1);
  std::ofstream(list, std::ios::app) << (dir / "gone").string() << "\n";
  const auto started = std::chrono::steady_clock::now();
  const auto r = e2e::surrogate("batch " + quote(list) + " -o " + quote(dir / "ledger.jsonl") + " --no-report --retries 0");
  const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - started).count();
  INFO(r.output);
  CHECK(r.exitCode == 1);
  CHECK(seconds < 60);
  CHECK(r.output.find("wait  ") == std::string::npos);
  CHECK(r.output.find((dir / "gone").string() + ": run FAILED (exit 1): " + (dir / "gone").string() +
                      ": the capture folder does not exist") != std::string::npos);
  const std::vector<json> lines = ledgerLines(dir / "ledger.jsonl");
  CHECK(count(lines, (dir / "gone").string(), "run", 1) == 1);
  CHECK(count(lines, (dir / "cap1").string(), "verify", 0) == 1);
}

TEST_CASE("a pack the ledger did not record is found and recorded and not made again", "[batch]") {
  const fs::path dir = e2e::freshDir("batch-adopt");
  const fs::path list = makeCaptures(dir, 2);
  const fs::path ledger = dir / "ledger.jsonl";
  const std::string command = "batch " + quote(list) + " -o " + quote(ledger) + " --no-report --quiet";
  REQUIRE(e2e::surrogate(command + " --do run,pack").exitCode == 0);
  // The batch was killed between the end of cap2's pack and its line: the line is not there.
  std::vector<json> lines = ledgerLines(ledger);
  {
    std::ofstream out(ledger, std::ios::trunc);
    for (const json& j : lines)
      if (!(j["capture"] == (dir / "cap2").string() && j["step"] == "pack")) out << j.dump() << "\n";
  }
  const std::string packaged = sha(dir / "cap2.zip");
  const auto mtime = fs::last_write_time(dir / "cap2.zip");
  REQUIRE(e2e::surrogate(command).exitCode == 0);
  lines = ledgerLines(ledger);
  CHECK(sha(dir / "cap2.zip") == packaged);
  CHECK(fs::last_write_time(dir / "cap2.zip") == mtime);
  bool adopted = false;
  for (const json& j : lines)
    if (j["capture"] == (dir / "cap2").string() && j["step"] == "pack") {
      adopted = j["adopted"] == true && j["exit"] == 0 && j["packageSha256"] == packaged;
      CHECK(j["message"].get<std::string>().find("without packing again") != std::string::npos);
    }
  CHECK(adopted);
  CHECK(count(lines, (dir / "cap2").string(), "verify", 0) == 1);

  // A file of that name that is not this capture's package is left alone, and said so.
  fs::remove(dir / "cap1.zip");
  std::ofstream(dir / "cap1.zip") << "someone else's file";
  const auto refused = e2e::surrogate(command);
  CHECK(refused.exitCode == 1);
  CHECK(e2e::bytesOf(dir / "cap1.zip") == "someone else's file");
  lines = ledgerLines(ledger);
  CHECK(lines.back()["step"] == "pack");
  CHECK(lines.back()["message"].get<std::string>().find("move it away") != std::string::npos);
}

TEST_CASE("a job over its memory budget is stopped with a message in the ledger while the others go on", "[batch]") {
  const fs::path dir = e2e::freshDir("batch-memory");
  makeCaptures(dir, 1);
  // A capture of 12 photographs at 1200x800 whose run with its report passes 64 MB, the least
  // a job gets (measured: 76-83 MB resident with run --memory 64M; the report's models were
  // reduced to a byte budget since the 120 MB first measured; at 70M the suite under load saw
  // it pass once), beside one of 6 at 200x150 (40 MB).
  const fs::path big = dir / "big";
  REQUIRE(e2e::runShell(std::string(GENERATOR_EXE) + " --out " + quote(big) +
                        " --images 12 --width 1200 --height 800 --seed 3").exitCode == 0);
  fs::remove_all(big / "truth");
  std::ofstream(dir / "list.txt") << big.string() << "\n" << (dir / "cap1").string() << "\n";
  const fs::path ledger = dir / "ledger.jsonl";
  const auto r = e2e::surrogate("batch " + quote(dir / "list.txt") + " -o " + quote(ledger) +
                                " --do run --memory 64M --threads 1 --retries 2");
  INFO(r.output);
  CHECK(r.exitCode == 5);
  const std::vector<json> lines = ledgerLines(ledger);
  REQUIRE(lines.size() == 2);  // a budget passed is not retried
  CHECK(lines[0]["capture"] == big.string());
  CHECK(lines[0]["exit"] == 137);
  CHECK(lines[0]["memoryBudget"] == 64ull << 20);
  CHECK(lines[0]["peakMemory"].get<std::uint64_t>() > (64ull << 20));
  CHECK(lines[0]["message"].get<std::string>().find("passed the budget of 64M per job (--memory)") != std::string::npos);
  CHECK(lines[1]["capture"] == (dir / "cap1").string());
  CHECK(lines[1]["exit"] == 0);
  CHECK(r.output.find("FAIL  " + big.string() + ": run FAILED (exit 137)") != std::string::npos);
}

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

TEST_CASE("GNU parallel runs the script batch --emit parallel writes and reruns only the failed job", "[batch]") {
  if (e2e::runShell("parallel --version").exitCode != 0) {
    WARN("GNU parallel is not installed (scripts/install-deps installs Debian's parallel): test skipped");
    return;
  }
  const fs::path dir = e2e::freshDir("batch-parallel");
  const fs::path list = makeCaptures(dir, 3);
  // A fourth line that is not a capture yet: its job fails, the others do not wait for it.
  std::ofstream(list, std::ios::app) << (dir / "late").string() << "\n";
  fs::create_directories(dir / "late");
  const fs::path ledger = dir / "ledger.jsonl";
  const auto emitted = e2e::surrogate("batch " + quote(list) + " -o " + quote(ledger) +
                                      " --jobs 2 --memory 1G --no-report --emit parallel");
  REQUIRE(emitted.exitCode == 0);
  CHECK(emitted.output.find("--joblog") != std::string::npos);
  CHECK(emitted.output.find("--resume-failed") != std::string::npos);
  CHECK(emitted.output.find("--memfree 1G") != std::string::npos);
  CHECK(emitted.output.find(" --one {") != std::string::npos);  // the item number, the last input source
  CHECK(emitted.output.find("--null") != std::string::npos);
  CHECK(emitted.output.find("--quote") != std::string::npos);
  std::ofstream(dir / "run.sh") << emitted.output;
  const auto first = e2e::runShell("cd " + quote(dir) + " && HOME=" + quote(dir) + " sh run.sh");
  INFO(first.output);
  CHECK(first.exitCode == 1);  // parallel: the number of failed jobs
  std::vector<json> lines = ledgerLines(ledger);
  for (int i = 1; i <= 3; ++i) CHECK(count(lines, (dir / ("cap" + std::to_string(i))).string(), "verify", 0) == 1);
  CHECK(count(lines, (dir / "late").string(), "run", 0) == 0);
  const std::size_t linesBefore = lines.size();
  // The capture arrives; the script run again reruns the failed job only.
  fs::remove_all(dir / "late");
  REQUIRE(e2e::runShell(std::string(GENERATOR_EXE) + " --out " + quote(dir / "late") +
                        " --images 6 --width 200 --height 150 --sphere-radius 25 --seed 9").exitCode == 0);
  fs::remove_all(dir / "late" / "truth");
  const auto second = e2e::runShell("cd " + quote(dir) + " && HOME=" + quote(dir) + " sh run.sh");
  INFO(second.output);
  CHECK(second.exitCode == 0);
  lines = ledgerLines(ledger);
  CHECK(lines.size() == linesBefore + 3);  // late's run, pack and verify; nothing else again
  CHECK(count(lines, (dir / "late").string(), "verify", 0) == 1);
  // parallel's own job log: one line per job and run (a header, 4 jobs, then the one rerun).
  std::ifstream joblog(ledger.string() + ".joblog");
  std::size_t jobLines = 0;
  std::string line;
  while (std::getline(joblog, line)) ++jobLines;
  CHECK(jobLines == 1 + 4 + 1);
  CHECK(e2e::surrogate("batch --summary -o " + quote(ledger)).exitCode == 0);
}

namespace {

// A single-host Slurm cluster in a scratch folder: munged with its own key and socket,
// slurmctld and slurmd (Debian's munge and slurm-wlm) on two free ports, stopped (by their
// process ids) when the test ends. `error` says why it could not start.
class SlurmCluster {
  // The cluster's folder directly under /tmp, whatever TMPDIR says: slurmstepd makes a Unix
  // socket in SlurmdSpoolDir, whose path may not pass 108 bytes (under scripts/test's TMPDIR
  // it was 115, and every batch launch failed).
  static fs::path shortScratchDir() {
    std::string path = "/tmp/surrogate-slurm-XXXXXX";
    if (!::mkdtemp(path.data())) throw std::runtime_error("cannot make a folder for the Slurm cluster in /tmp");
    return path;
  }

 public:
  SlurmCluster() : dir_(shortScratchDir()) {
    for (const char* tool : {"munged", "slurmctld", "slurmd", "sbatch", "squeue", "scontrol", "sinfo"})
      if (e2e::runShell(std::string("command -v ") + tool + " || test -x /usr/sbin/" + tool).exitCode != 0) {
        error = std::string(tool) + " is not installed (scripts/install-deps installs Debian's slurm-wlm and munge)";
        return;
      }
    fs::create_directories(dir_ / "munge");
    fs::permissions(dir_ / "munge", fs::perms::owner_all, fs::perm_options::replace);
    for (const char* sub : {"state", "spool", "log"}) fs::create_directories(dir_ / sub);
    const std::string d = quote(dir_);
    if (e2e::runShell("dd if=/dev/urandom of=" + d + "/munge/munge.key bs=1024 count=1 2>/dev/null && chmod 600 " + d +
                      "/munge/munge.key").exitCode != 0) {
      error = "cannot make a munge key";
      return;
    }
    const auto munge = e2e::runShell("PATH=\"$PATH:/usr/sbin\" munged -f --key-file=" + d + "/munge/munge.key --socket=" + d +
                                     "/munge/socket --pid-file=" + d + "/munge/munged.pid --log-file=" + d +
                                     "/log/munged.log --seed-file=" + d + "/munge/seed");
    if (munge.exitCode != 0) {
      error = "munged did not start: " + munge.output;
      return;
    }
    mungeStarted_ = true;
    const std::string host = trimmed(e2e::runShell("hostname -s").output);
    const std::string user = trimmed(e2e::runShell("id -un").output);
    const int port = 20000 + static_cast<int>(::getpid() % 20000);
    const long memoryMb = sysconf(_SC_PHYS_PAGES) / 1024 * sysconf(_SC_PAGESIZE) / 1024;
    std::ofstream conf(dir_ / "slurm.conf");
    conf << "ClusterName=surrogate-test\nSlurmctldHost=" << host << "(127.0.0.1)\n"
         << "SlurmctldPort=" << port << "\nSlurmdPort=" << port + 1 << "\n"
         << "AuthType=auth/munge\nAuthInfo=socket=" << dir_.string() << "/munge/socket\nCredType=cred/munge\n"
         << "SlurmUser=" << user << "\nSlurmdUser=" << user << "\n"
         << "StateSaveLocation=" << dir_.string() << "/state\nSlurmdSpoolDir=" << dir_.string() << "/spool\n"
         << "SlurmctldPidFile=" << dir_.string() << "/slurmctld.pid\nSlurmdPidFile=" << dir_.string() << "/slurmd.pid\n"
         << "SlurmctldLogFile=" << dir_.string() << "/log/slurmctld.log\nSlurmdLogFile=" << dir_.string() << "/log/slurmd.log\n"
         << "ProctrackType=proctrack/linuxproc\nTaskPlugin=task/none\n"
         << "SelectType=select/cons_tres\nSelectTypeParameters=CR_Core_Memory\n"
         << "JobAcctGatherType=jobacct_gather/none\nAccountingStorageType=accounting_storage/none\n"
         << "MpiDefault=none\nReturnToService=2\nJobRequeue=1\nSchedulerParameters=sched_interval=1\n"
         << "NodeName=" << host << " NodeAddr=127.0.0.1 CPUs=" << sysconf(_SC_NPROCESSORS_ONLN)
         << " RealMemory=" << memoryMb / 2 << " State=UNKNOWN\n"
         << "PartitionName=batch Nodes=ALL Default=YES MaxTime=INFINITE State=UP\n";
    conf.close();
    env_ = "export SLURM_CONF=" + quote(dir_ / "slurm.conf") + " PATH=\"$PATH:/usr/sbin\"; ";
    if (e2e::runShell(env_ + "slurmctld -i -f " + quote(dir_ / "slurm.conf")).exitCode != 0 ||
        e2e::runShell(env_ + "slurmd -f " + quote(dir_ / "slurm.conf")).exitCode != 0) {
      error = "slurmctld or slurmd did not start: " + e2e::bytesOf(dir_ / "log/slurmctld.log") +
              e2e::bytesOf(dir_ / "log/slurmd.log");
      return;
    }
    for (int i = 0; i < 100; ++i) {
      if (trimmed(run("sinfo -h -o %T").output) == "idle") return;
      std::this_thread::sleep_for(std::chrono::milliseconds(200));
    }
    error = "the node did not become idle in 20 s: " + run("sinfo").output + e2e::bytesOf(dir_ / "log/slurmd.log");
  }

  ~SlurmCluster() {
    run("scancel --user=$(id -un)");
    // Only the daemons this test started, by the process ids they wrote.
    for (const char* pidFile : {"slurmd.pid", "slurmctld.pid", "munge/munged.pid"}) {
      const std::string pid = trimmed(e2e::bytesOf(dir_ / pidFile));
      if (!pid.empty() && pid.find_first_not_of("0123456789") == std::string::npos) {
        ::kill(std::stoi(pid), SIGTERM);
        for (int i = 0; i < 50 && ::kill(std::stoi(pid), 0) == 0; ++i)
          std::this_thread::sleep_for(std::chrono::milliseconds(100));
      }
    }
    std::error_code ec;
    fs::remove_all(dir_, ec);
  }

  e2e::CommandResult run(const std::string& command) const { return e2e::runShell(env_ + command); }

  // The daemons' last log lines, to say why a job did not start.
  std::string logTail() const {
    return e2e::runShell("tail -n 15 " + quote(dir_ / "log/slurmd.log") + " " + quote(dir_ / "log/slurmctld.log")).output;
  }

  std::string error;

 private:
  static std::string trimmed(std::string s) {
    while (!s.empty() && (s.back() == '\n' || s.back() == ' ')) s.pop_back();
    return s;
  }
  fs::path dir_;
  std::string env_;
  bool mungeStarted_ = false;
};

}  // namespace

TEST_CASE("a Slurm job array does the batch with one task killed and requeued and the ledger shows each capture done once",
          "[batch][slurm]") {
  // The captures, list and ledger under a folder with a space (sbatch splits #SBATCH values
  // at blanks); the cluster's own files apart (SlurmCluster: a short path).
  const fs::path dir = e2e::freshDir("batch slurm");
  SlurmCluster cluster;
  if (!cluster.error.empty()) {
    WARN("single-host Slurm cluster could not start, test skipped: " << cluster.error);
    return;
  }
  const fs::path list = makeCaptures(dir, 6);
  const fs::path ledger = dir / "ledger.jsonl";
  const auto emitted = e2e::runShell("cd " + quote(dir) + " && " + SURROGATE_EXE + " batch " + quote(list) + " -o " +
                                     quote(ledger) + " --jobs 2 --memory 512M --no-report --emit slurm");
  REQUIRE(emitted.exitCode == 0);
  CHECK(emitted.output.find("#SBATCH --array=1-6%2") != std::string::npos);
  CHECK(emitted.output.find("#SBATCH --mem=640M") != std::string::npos);
  CHECK(emitted.output.find("#SBATCH --requeue") != std::string::npos);
  // Task 1's first attempt does the run step, then hangs where a slow pack would be, so that
  // the test kills it while it runs whatever the machine's speed (polling for a short task in
  // the R state missed it on a fast machine). The requeued attempt must take the capture on
  // from there: its run not redone, one pack.
  const std::string script = emitted.output;
  const std::size_t execAt = script.find("\nexec ");
  REQUIRE(execAt != std::string::npos);
  std::string command = script.substr(execAt + 6);
  command = command.substr(0, command.find('\n'));
  const fs::path hanging = dir / "task1-hanging";
  std::ofstream(dir / "array.sh") << script.substr(0, execAt + 1)
                                  << "if [ \"$SLURM_ARRAY_TASK_ID\" = 1 ] && [ \"${SLURM_RESTART_COUNT:-0}\" = 0 ]; then\n  "
                                  << command << " --do run\n  touch " << quote(hanging) << "\n  sleep 600\nfi\n"
                                  << script.substr(execAt + 1);
  const auto submitted = cluster.run("cd " + quote(dir) + " && sbatch --parsable " + quote(dir / "array.sh"));
  INFO(submitted.output);
  REQUIRE(submitted.exitCode == 0);
  const std::string job = submitted.output.substr(0, submitted.output.find_first_of(";\n"));
  bool requeued = false;
  bool launchFailed = false;
  for (int i = 0; i < 1200 && !requeued && !launchFailed; ++i) {
    if (fs::exists(hanging)) requeued = cluster.run("scontrol requeue " + job + "_1").exitCode == 0;
    else std::this_thread::sleep_for(std::chrono::milliseconds(100));
    launchFailed = cluster.run("squeue -h -o %r").output.find("launch failed") != std::string::npos;
  }
  INFO(cluster.run("squeue").output << cluster.logTail());
  REQUIRE(!launchFailed);
  REQUIRE(requeued);
  bool released = false;
  for (int i = 0; i < 300 && !released; ++i) {
    // Once the kill is complete, the task waits for its begin time: moved to now.
    if (cluster.run("squeue -h -j " + job + "_1 -o %r").output.find("BeginTime") != std::string::npos)
      released = cluster.run("scontrol update jobid=" + job + "_1 StartTime=now").exitCode == 0;
    if (!released) std::this_thread::sleep_for(std::chrono::milliseconds(100));
  }
  CHECK(released);
  bool finished = false;
  for (int i = 0; i < 600 && !finished; ++i) {
    finished = cluster.run("squeue -h -j " + job).output.empty();
    if (!finished) std::this_thread::sleep_for(std::chrono::milliseconds(200));
  }
  REQUIRE(finished);
  CHECK(cluster.run("scontrol show job " + job + "_1").output.find("Restarts=1") != std::string::npos);
  // The tasks' output where the script's quoted #SBATCH --output put it, space and all.
  CHECK(fs::exists(dir / ("ledger.jsonl.slurm-" + job + "_1.out")));
  CHECK(fs::exists(dir / ("ledger.jsonl.slurm-" + job + "_6.out")));

  const auto summary = e2e::surrogate("batch --summary -o " + quote(ledger) + " --json");
  INFO(summary.output << e2e::bytesOf(ledger));
  CHECK(summary.exitCode == 0);
  const json s = json::parse(summary.output);
  CHECK(s["items"] == 6);
  CHECK(s["done"] == 6);
  CHECK(s["failed"] == 0);
  const std::vector<json> lines = ledgerLines(ledger);
  for (int i = 1; i <= 6; ++i) {
    const std::string cap = (dir / ("cap" + std::to_string(i))).string();
    CHECK(count(lines, cap, "run", 0) == 1);
    CHECK(count(lines, cap, "pack", 0) == 1);
    CHECK(count(lines, cap, "verify", 0) == 1);
  }
}
