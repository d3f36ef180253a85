// surrogate batch under attack by names: the scripts --emit writes run no command a name holds
// (GNU parallel and sh really run them), list items are paths and never options, a list that
// is no list (a device, a FIFO, an endless stream) is refused at once, one capture under two
// spellings is one item, and names are printed escaped. One small generated capture is reused.
#include <catch2/catch.hpp>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "e2e_support.h"
#include "ledger_lines.h"

namespace fs = std::filesystem;
using e2e::quote;
using nlohmann::json;

namespace {

// A name holding every way a shell or GNU parallel could be made to run a command: $(),
// backticks, ;, both quotes, parallel's replacement strings ({} and {= perl =}). Each command
// would make a file named MARK... in the folder it runs in.
const std::string kHostile =
    "$(touch MARK1)`touch MARK2`;touch MARK3;'q\"{}{= system(\"touch MARK4\") =}";

std::vector<std::string> markers(const fs::path& dir) {
  std::vector<std::string> out;
  for (const auto& entry : fs::recursive_directory_iterator(dir))
    if (entry.path().filename().string().rfind("MARK", 0) == 0) out.push_back(entry.path().string());
  return out;
}

using e2e::ledgerLines;

// The exit code of the last line of `capture`'s `step` in the ledger; -1 when there is none.
int lastExit(const std::vector<json>& lines, const std::string& capture, const std::string& step) {
  int exit = -1;
  for (const json& j : lines)
    if (j["capture"] == capture && j["step"] == step) exit = j["exit"].get<int>();
  return exit;
}

// A capture folder named `name` in `dir` (a copy of the one generated capture).
void captureNamed(const fs::path& dir, const std::string& name) {
  const fs::path made = e2e::smallCapture(dir, 6);
  fs::rename(made, dir / name);
}

}  // namespace

TEST_CASE("the script batch --emit parallel writes runs no command from a name and GNU parallel does the jobs",
          "[batch][hostile]") {
  if (e2e::runShell("parallel --version").exitCode != 0) {
    WARN("GNU parallel is not installed (scripts/install-deps installs Debian's parallel): test skipped");
    return;
  }
  const fs::path dir = e2e::freshDir("batch-hostile-parallel");
  captureNamed(dir, "-h");  // a capture folder that reads as an option
  // The list, the ledger and the packages folder hold the hostile name, a line break, a space
  // and a leading dash; the list holds the capture "-h" and the item "--help".
  const std::string list = "-l " + kHostile + "\nx.txt";
  const std::string ledger = "-led " + kHostile + ".jsonl";
  const std::string packages = "-pk;touch MARK5;\n" + kHostile;
  std::ofstream(dir / list) << "-h\n--help\n";
  fs::create_directory(dir / packages);
  const auto emitted = e2e::runShell("cd " + quote(dir) + " && " + SURROGATE_EXE + " batch ./" + quote(list) +
                                     " -o ./" + quote(ledger) + " --packages ./" + quote(packages) +
                                     " --do run,pack,verify --no-report --jobs 2 --emit parallel > run.sh");
  INFO(emitted.output);
  REQUIRE(emitted.exitCode == 0);
  const auto ran = e2e::runShell("cd " + quote(dir) + " && HOME=" + quote(dir) + " sh run.sh");
  INFO(ran.output);
  INFO(e2e::bytesOf(dir / "run.sh"));
  CHECK(ran.exitCode == 1);  // parallel: one failed job, --help's (no such capture)
  CHECK(markers(dir).empty());
  const std::vector<json> lines = ledgerLines(dir / ledger);
  CHECK(lastExit(lines, "-h", "run") == 0);
  CHECK(lastExit(lines, "-h", "pack") == 0);
  CHECK(lastExit(lines, "-h", "verify") == 0);
  CHECK(lastExit(lines, "--help", "run") == 1);
  CHECK(fs::is_regular_file(dir / packages / "-h.zip"));
  CHECK(fs::exists(dir / (ledger + ".joblog")));

  // The Slurm script of the same batch (sbatch cannot take a line break in the list's or the
  // ledger's path: a list without one), run by sh as a task would run it: the item is done,
  // so the task finds it so, and no command ran from a name.
  const std::string slurmList = "-s " + kHostile + ".txt";
  fs::copy_file(dir / list, dir / slurmList);
  const auto slurm = e2e::runShell("cd " + quote(dir) + " && " + SURROGATE_EXE + " batch ./" + quote(slurmList) +
                                   " -o ./" + quote(ledger) + " --packages ./" + quote(packages) +
                                   " --do run,pack,verify --no-report --emit slurm > task.sbatch && sh -n task.sbatch");
  INFO(slurm.output);
  REQUIRE(slurm.exitCode == 0);
  const auto task = e2e::runShell("cd / && SLURM_ARRAY_TASK_ID=1 sh " + quote(dir / "task.sbatch"));
  INFO(task.output);
  INFO(e2e::bytesOf(dir / "task.sbatch"));
  CHECK(task.exitCode == 0);
  CHECK(markers(dir).empty());
  CHECK(ledgerLines(dir / ledger).size() == lines.size());  // done before: nothing run again
}

TEST_CASE("list items are paths: a capture named -h is processed and an item --help fails as no capture",
          "[batch][hostile]") {
  const fs::path dir = e2e::freshDir("batch-hostile-items");
  captureNamed(dir, "-h");
  captureNamed(dir, "lat\xE9");  // a name that is not UTF-8: run refuses it (exit 1)
  std::ofstream(dir / "list.txt") << "-h\n--help\nno\tsuch\nlat\xE9\n";
  const auto r = e2e::runShell("cd " + quote(dir) + " && " + SURROGATE_EXE +
                               " batch list.txt -o ledger.jsonl --do run,pack --no-report");
  INFO(r.output);
  CHECK(r.exitCode == 1);  // failed steps of bad input: not 5, no signal
  CHECK(fs::is_regular_file(dir / "-h.zip"));
  CHECK(e2e::surrogate("verify " + quote(dir / "-h.zip") + " --quiet").exitCode == 0);
  const std::vector<json> lines = ledgerLines(dir / "ledger.jsonl");
  CHECK(lastExit(lines, "-h", "pack") == 0);
  CHECK(lastExit(lines, "--help", "run") == 1);
  CHECK(lastExit(lines, "no\tsuch", "run") == 1);
  // The name that is not UTF-8 (recorded escaped, as every name the ledger cannot hold as
  // text): run refuses it with exit 1.
  CHECK(lastExit(lines, "lat\\xE9", "run") == 1);
  // One line per job, the names escaped: no tab, no byte that is not UTF-8.
  CHECK(r.output.find("FAIL  no\\x09such: run FAILED (exit 1)") != std::string::npos);
  CHECK(r.output.find("FAIL  lat\\xE9: run ") != std::string::npos);
  CHECK(r.output.find('\t') == std::string::npos);
  CHECK(r.output.find('\xE9') == std::string::npos);

  // A capture processed under another name, then renamed to one that is not UTF-8: its pack is
  // refused (exit 1, pack's message), reported as any failed step, never as a signal or 5.
  fs::rename(e2e::processedCapture(dir), dir / "old\xE9");
  std::ofstream(dir / "renamed.txt") << "old\xE9\n";
  const auto packed = e2e::runShell("cd " + quote(dir) + " && " + SURROGATE_EXE +
                                    " batch renamed.txt -o renamed.jsonl --do pack,verify --no-report");
  INFO(packed.output);
  CHECK(packed.exitCode == 1);
  CHECK(lastExit(ledgerLines(dir / "renamed.jsonl"), "old\\xE9", "pack") == 1);
  CHECK(packed.output.find("FAIL  old\\xE9: pack FAILED (exit 1): old\\xE9.zip: ") != std::string::npos);
  CHECK(packed.output.find("by signal") == std::string::npos);
  CHECK(!fs::exists(dir / "old\xE9.zip"));

  // --summary of a ledger whose item holds a line break, an escape sequence and a C1 control:
  // each shown as \xHH on its own line, no line forged.
  json forged = lines.front();
  forged["capture"] = "a\tb\nFAIL  forged\x1b[2J\xc2\x9b";
  forged["exit"] = 1;
  std::ofstream(dir / "ledger.jsonl", std::ios::app) << forged.dump() << "\n";
  const auto summary = e2e::surrogate("batch --summary -o " + quote(dir / "ledger.jsonl"));
  INFO(summary.output);
  CHECK(summary.output.find("  FAIL  a\\x09b\\x0AFAIL  forged\\x1B[2J\\xC2\\x9B") != std::string::npos);
  CHECK(summary.output.find('\t') == std::string::npos);
  CHECK(summary.output.find('\x1b') == std::string::npos);
  CHECK(summary.output.find("\nFAIL  forged") == std::string::npos);
}

TEST_CASE("one capture under two spellings in a list is refused naming both lines before any job",
          "[batch][hostile]") {
  const fs::path dir = e2e::freshDir("batch-hostile-spellings");
  fs::create_directories(dir / "cap");
  fs::create_directory_symlink("cap", dir / "link");
  std::ofstream(dir / "list.txt") << "cap\n" << (dir / "link").string() << "\n";
  const auto r = e2e::runShell("cd " + quote(dir) + " && " + SURROGATE_EXE + " batch list.txt -o ledger.jsonl");
  INFO(r.output);
  CHECK(r.exitCode == 2);
  CHECK(r.output.find("line 2 (" + (dir / "link").string() + ") repeats line 1 (cap), both " +
                      fs::canonical(dir / "cap").string()) != std::string::npos);
  CHECK((!fs::exists(dir / "ledger.jsonl") || fs::file_size(dir / "ledger.jsonl") == 0));
}

TEST_CASE("a list that is a device a FIFO or an endless stream is refused with exit 1 at once", "[batch][hostile]") {
  const fs::path dir = e2e::freshDir("batch-hostile-lists");
  REQUIRE(e2e::runShell("mkfifo " + quote(dir / "list.fifo")).exitCode == 0);
  const std::string batch = std::string("timeout 30 ") + SURROGATE_EXE + " batch ";
  const std::string ledger = " -o " + quote(dir / "ledger.jsonl");
  struct Case {
    std::string shell, says;
  };
  for (const Case& c : {Case{batch + "/dev/zero" + ledger, "/dev/zero: is not a regular file (a device"},
                        Case{batch + quote(dir / "list.fifo") + ledger, "list.fifo: is not a regular file (a FIFO)"},
                        Case{batch + "-" + ledger + " < /dev/zero", "line 1 holds a NUL byte"},
                        Case{"yes | " + batch + "-" + ledger, "is larger than 64 MiB"},
                        Case{"head -c 100000 /dev/zero | tr '\\0' a | " + batch + "-" + ledger,
                             "line 1 is longer than 4096 bytes"}}) {
    INFO(c.shell);
    const auto r = e2e::runShell(c.shell);
    INFO(r.output);
    CHECK(r.exitCode == 1);  // 124 when timeout had to stop it
    CHECK(r.output.find(c.says) != std::string::npos);
  }
}
