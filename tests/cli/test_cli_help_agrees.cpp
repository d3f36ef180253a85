// What every --help says against what the program does: the exit codes it lists are those the
// table below says the command returns (kept beside the codes' sources: core/error.h's kinds,
// and core/atomic_file.h, which reports a refused write as bad input, 1), each triggered where
// a test can; every example's command line is taken by the command's parser; and the commands
// that print take --quiet and --verbose with a meaning.
#include <catch2/catch.hpp>

#include <fstream>

#include <algorithm>
#include <filesystem>
#include <map>
#include <regex>
#include <set>
#include <sstream>

#include "e2e_support.h"

namespace fs = std::filesystem;
using Catch::Contains;

namespace {

// The codes each command returns. 3: run, lights and pack refuse a changed original, publish a
// changed result, info, report and audit a damaged archive; 4: verify --reexecute and audit
// (and batch, which runs verify); 5 is a bug or memory, for all (a damaged installation is 1).
const std::map<std::string, std::set<int>> kExitCodes = {
    {"run", {0, 1, 2, 3, 5}},     {"pack", {0, 1, 2, 3, 5}},   {"lights", {0, 1, 2, 3, 5}},
    {"fit", {0, 1, 2, 5}},        {"render", {0, 1, 2, 5}},    {"publish", {0, 1, 2, 3, 5}},
    {"info", {0, 1, 2, 3, 5}},    {"report", {0, 1, 2, 3, 5}}, {"review", {0, 1, 2, 5}},
    {"verify", {0, 1, 2, 3, 4, 5}}, {"audit", {0, 1, 2, 3, 4, 5}}, {"batch", {0, 1, 2, 3, 4, 5}},
};

// A command line of each command whose input is missing: exit 1, once the options are parsed.
const std::map<std::string, std::string> kMissingInput = {
    {"run", "run missing"},
    {"pack", "pack missing -o out.zip"},
    {"lights", "lights missing -o out.lp"},
    {"fit", "fit --lp missing.lp -o out.ptm"},
    {"render", "render missing.ptm --light 0,0,1 -o out.png"},
    {"publish", "publish missing.ptm -o web-out"},
    {"info", "info missing"},
    {"report", "report missing -o out.html"},
    {"review", "review missing --no-browser"},
    {"verify", "verify missing.zip"},
    {"audit", "audit missing"},
    {"batch", "batch missing.txt -o ledger.jsonl"},
};

// The --help's "exit codes:" block: each line "  N  meaning" (and its wrapped lines).
std::map<int, std::string> helpExitCodes(const std::string& help) {
  std::map<int, std::string> codes;
  std::istringstream in(help.substr(help.find("\nexit codes:\n") + 13));
  int last = -1;
  for (std::string line; std::getline(in, line) && !line.empty();) {
    std::smatch m;
    if (std::regex_match(line, m, std::regex("  ([0-9])  (.*)"))) codes[last = std::stoi(m[1])] = m[2];
    else if (last >= 0) codes[last] += " " + line.substr(line.find_first_not_of(' '));
  }
  return codes;
}

std::vector<std::string> helpExamples(const std::string& help) {
  std::vector<std::string> examples;
  std::istringstream in(help.substr(help.find("\nexamples:\n") + 11));
  for (std::string line; std::getline(in, line) && !line.empty();)
    if (line.rfind("  surrogate ", 0) == 0) examples.push_back(line.substr(2));
  return examples;
}

}  // namespace

TEST_CASE("every --help lists exactly the exit codes its command returns, in the same words", "[cli][help]") {
  for (const auto& [name, expected] : kExitCodes) {
    const e2e::CommandResult help = e2e::surrogate(name + " --help");
    INFO("surrogate " << name << " --help\n" << help.output);
    REQUIRE(help.exitCode == 0);
    const std::map<int, std::string> codes = helpExitCodes(help.output);
    std::set<int> listed;
    for (const auto& [code, meaning] : codes) listed.insert(code);
    CHECK(listed == expected);
    // A write the system refuses is exit 1 (core/atomic_file.h): never called exit 5.
    REQUIRE(codes.count(5));
    CHECK(codes.at(5).find("disk") == std::string::npos);
    CHECK(codes.at(5).find("permission") == std::string::npos);
  }
}

TEST_CASE("each command returns the usage and missing-input codes its --help lists", "[cli][help]") {
  const fs::path work = e2e::freshDir("help-codes");
  for (const auto& [name, missing] : kMissingInput) {
    const e2e::CommandResult usage = e2e::surrogate(name + " --no-such-option");
    INFO(name << ": " << usage.output);
    CHECK(usage.exitCode == 2);
    CHECK_THAT(usage.output, Contains("unknown option \"--no-such-option\""));
    const e2e::CommandResult r = e2e::runShell("cd " + e2e::quote(work) + " && " + SURROGATE_EXE + " " + missing);
    INFO(missing << ": " << r.output);
    CHECK(r.exitCode == 1);
    CHECK_THAT(r.output, Contains("missing"));
  }
}

TEST_CASE("a write the system refuses is exit 1 as help says, a changed original exit 3 for run", "[cli][help]") {
  const fs::path work = e2e::freshDir("help-write");
  const fs::path capture = e2e::processedCapture(work);
  const fs::path ptm = capture / "finished-files" / "ptm-lrgb.ptm";
  REQUIRE(fs::is_regular_file(ptm));  // the file render's example names
  // A file-size limit of one block: the picture cannot be written.
  const e2e::CommandResult refused = e2e::runShell("ulimit -f 1 && " + std::string(SURROGATE_EXE) + " render " +
                                                   e2e::quote(ptm) + " --light 0,0,1 -o " + e2e::quote(work / "big.png"));
  INFO(refused.output);
  CHECK(refused.exitCode == 1);
  CHECK_THAT(refused.output, Contains("big.png"));
  CHECK_FALSE(fs::exists(work / "big.png"));

  fs::path original;
  for (const auto& e : fs::directory_iterator(capture / "original-captures"))
    if (e.is_regular_file()) original = e.path();
  REQUIRE(!original.empty());
  e2e::runShell("printf x >> " + e2e::quote(original));
  const e2e::CommandResult changed = e2e::surrogate("run " + e2e::quote(capture) + " --quiet");
  INFO(changed.output);
  CHECK(changed.exitCode == 3);
  CHECK_THAT(changed.output, Contains(original.filename().string()));
}

TEST_CASE("every --help example is a command line its command takes", "[cli][help]") {
  for (const auto& [name, missing] : kMissingInput) {
    const e2e::CommandResult help = e2e::surrogate(name + " --help");
    for (const std::string& example : helpExamples(help.output)) {
      // In an empty folder with the output folders the examples name: every input is missing.
      const fs::path work = e2e::freshDir("help-example");
      fs::create_directories(work / "web");
      fs::create_directories(work / "repository");
      const e2e::CommandResult r = e2e::runShell("cd " + e2e::quote(work) + " && " + SURROGATE_EXE +
                                                 example.substr(std::string("surrogate").size()));
      INFO(example << "\n" << r.output);
      CHECK(r.exitCode == 1);
      CHECK(r.output.find("unknown option") == std::string::npos);
      CHECK(r.output.find("needs a value") == std::string::npos);
    }
  }
}

TEST_CASE("render, verify, fit, info, report, batch and review take --quiet and --verbose with a meaning", "[cli][help]") {
  for (const auto& [name, missing] : kMissingInput) {
    const e2e::CommandResult help = e2e::surrogate(name + " --help");
    INFO(name);
    CHECK_THAT(help.output, Contains("\n  --quiet "));
    CHECK_THAT(help.output, Contains("\n  --verbose "));
  }
  const fs::path work = e2e::freshDir("help-verbosity");
  const fs::path capture = e2e::processedCapture(work);
  const std::string ptm = e2e::quote(capture / "finished-files" / "ptm-lrgb.ptm");
  const std::string render = "render " + ptm + " --light 0.5,0,0.866 -o " + e2e::quote(work / "lit.png");
  const e2e::CommandResult quiet = e2e::surrogate(render + " --quiet");
  CHECK(quiet.exitCode == 0);
  CHECK(quiet.output.empty());
  const e2e::CommandResult verbose = e2e::surrogate(render + " --verbose");
  INFO(verbose.output);
  CHECK(verbose.exitCode == 0);
  CHECK_THAT(verbose.output, Contains("elevation 60.0 deg, azimuth 0.0 deg"));
  CHECK(e2e::surrogate(render + " --quiet --verbose").exitCode == 2);

  const e2e::CommandResult infoQuiet = e2e::surrogate("info " + e2e::quote(capture) + " --quiet");
  CHECK(infoQuiet.exitCode == 0);
  CHECK(infoQuiet.output.empty());
  const e2e::CommandResult infoVerbose = e2e::surrogate("info " + e2e::quote(capture) + " --verbose");
  INFO(infoVerbose.output);
  CHECK(infoVerbose.exitCode == 0);
  CHECK(std::regex_search(infoVerbose.output, std::regex("original-captures/[^ ]+  original, [0-9]+ bytes, [0-9a-f]{64}")));

  const fs::path package = work / "cap.zip";
  REQUIRE(e2e::surrogate("pack " + e2e::quote(capture) + " -o " + e2e::quote(package) + " --quiet").exitCode == 0);
  const e2e::CommandResult verifyVerbose = e2e::surrogate("verify " + e2e::quote(package) + " --verbose");
  INFO(verifyVerbose.output);
  CHECK(verifyVerbose.exitCode == 0);
  CHECK_THAT(verifyVerbose.output, Contains("a failure here: fixity failure (exit 3)"));
  CHECK_THAT(verifyVerbose.output, Contains("a failure here: invalid package (exit 2)"));

  const std::string fit = "fit --lp " + e2e::quote(capture / "assembly-files" / "lights.lp") + " -o " +
                          e2e::quote(work / "fit.ptm") + " --holdout 2";
  const e2e::CommandResult fitQuiet = e2e::surrogate(fit + " --quiet");
  INFO(fitQuiet.output);
  CHECK(fitQuiet.exitCode == 0);
  CHECK(std::count(fitQuiet.output.begin(), fitQuiet.output.end(), '\n') == 1);
  const e2e::CommandResult fitVerbose = e2e::surrogate(fit + " --verbose");
  INFO(fitVerbose.output);
  CHECK(fitVerbose.exitCode == 0);
  CHECK_THAT(fitVerbose.output, Contains("condition number of the lights"));
  CHECK(std::regex_search(fitVerbose.output, std::regex("  left out [^ ]+: PSNR [0-9.]+ dB, SSIM [0-9.]+")));

  // report: quiet is its one line; verbose adds each check of --verify and the record's warnings.
  const std::string report = "report " + e2e::quote(package) + " --verify -o " + e2e::quote(work / "r.html");
  const e2e::CommandResult reportQuiet = e2e::surrogate(report + " --quiet");
  INFO(reportQuiet.output);
  CHECK(reportQuiet.exitCode == 0);
  CHECK(std::count(reportQuiet.output.begin(), reportQuiet.output.end(), '\n') == 1);
  const e2e::CommandResult reportVerbose = e2e::surrogate(report + " --verbose");
  INFO(reportVerbose.output);
  CHECK(reportVerbose.exitCode == 0);
  CHECK(std::regex_search(reportVerbose.output, std::regex("\n    ok   [a-z]")));
  CHECK(std::regex_search(reportVerbose.output, std::regex("\n  (warnings: none in the record|[0-9]+ warnings? in the carrier's log:)\n")));
  CHECK(e2e::surrogate(report + " --quiet --verbose").exitCode == 2);

  // batch: quiet is its one summary line; verbose says each item's plan first and each step's attempts.
  std::ofstream(work / "list.txt") << "cap.zip\n";
  const std::string batch = "batch " + e2e::quote(work / "list.txt") + " -o " + e2e::quote(work / "ledger.jsonl");
  const e2e::CommandResult batchVerbose = e2e::surrogate(batch + " --verbose");
  INFO(batchVerbose.output);
  CHECK(batchVerbose.exitCode == 0);
  CHECK_THAT(batchVerbose.output, Contains("\nplan  cap.zip: verify"));
  CHECK_THAT(batchVerbose.output, Contains("\n      verify: done after 1 attempt in this batch\n"));
  const e2e::CommandResult batchQuiet = e2e::surrogate(batch + " --quiet");
  INFO(batchQuiet.output);
  CHECK(batchQuiet.exitCode == 0);
  CHECK(std::count(batchQuiet.output.begin(), batchQuiet.output.end(), '\n') == 1);
  CHECK(e2e::surrogate(batch + " --quiet --verbose").exitCode == 2);
}
