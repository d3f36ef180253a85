// surrogate batch interrupted or beside other commands: a batch killed with kill -9 and run
// again, two batches on one list at once, a capture another command holds waited for, and a
// capture folder that does not exist failed at once rather than waited for.
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

#include "batch_e2e_support.h"
#include "e2e_support.h"
#include "ledger_lines.h"

namespace fs = std::filesystem;
using e2e::quote;
using nlohmann::json;
using namespace batch_e2e;

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
