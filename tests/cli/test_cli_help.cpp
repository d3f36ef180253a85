// What a user reads: every command's --help puts its own options first, under the group
// headings, with two examples and its exit codes before the long list of `surrogate run`'s
// options; --quiet prints one summary line and --verbose the long listings that the ordinary
// output folds (a tiled web copy writes hundreds of files).
#include <catch2/catch.hpp>

#include <algorithm>
#include <regex>
#include <set>
#include <sstream>
#include <vector>

#include "e2e_support.h"

namespace fs = std::filesystem;

namespace {

std::vector<std::string> linesOf(const std::string& text) {
  std::vector<std::string> lines;
  std::istringstream in(text);
  for (std::string line; std::getline(in, line);) lines.push_back(line);
  return lines;
}

// The index of the first line equal to `line`, or lines.size().
std::size_t lineIndex(const std::vector<std::string>& lines, const std::string& line) {
  return static_cast<std::size_t>(std::find(lines.begin(), lines.end(), line) - lines.begin());
}

std::vector<std::string> commandNames() {
  const e2e::CommandResult top = e2e::surrogate("--help");
  std::vector<std::string> names;
  std::istringstream lines(top.output.substr(top.output.find("commands:")));
  for (std::string line; std::getline(lines, line);) {
    std::smatch m;
    if (std::regex_match(line, m, std::regex("  ([a-z]+) +.*"))) names.push_back(m[1].str());
  }
  return names;
}

}  // namespace

TEST_CASE("every command's --help has grouped options, two examples of itself and its exit codes") {
  const std::vector<std::string> names = commandNames();
  REQUIRE(names.size() >= 10);
  const std::set<std::string> headings = {"input:", "processing:", "output:"};
  for (const std::string& name : names) {
    INFO("surrogate " << name << " --help");
    const e2e::CommandResult help = e2e::surrogate(name + " --help");
    REQUIRE(help.exitCode == 0);
    const std::vector<std::string> lines = linesOf(help.output);
    REQUIRE(lines.size() > 3);
    CHECK(lines[0].rfind("usage: surrogate " + name, 0) == 0);
    // Two examples, each a command line of this command with a line saying what it does.
    const std::size_t examples = lineIndex(lines, "examples:");
    REQUIRE(examples < lines.size());
    int shown = 0;
    for (std::size_t i = examples + 1; i < lines.size() && !lines[i].empty(); ++i)
      if (lines[i].rfind("  surrogate " + name + " ", 0) == 0) {
        ++shown;
        REQUIRE(i + 1 < lines.size());
        CHECK(lines[i + 1].rfind("      ", 0) == 0);
      }
    CHECK(shown == 2);
    // The exit codes, 0 first, after the examples.
    const std::size_t codes = lineIndex(lines, "exit codes:");
    REQUIRE(codes < lines.size());
    CHECK(codes > examples);
    REQUIRE(codes + 1 < lines.size());
    CHECK(lines[codes + 1].rfind("  0  ", 0) == 0);
    // Every option is listed once, and each under a heading.
    std::set<std::string> options;
    bool underHeading = false;
    for (std::size_t i = 0; i < examples; ++i) {
      const std::string& line = lines[i];
      if (!line.empty() && line.back() == ':' && line[0] != ' ') underHeading = true;
      std::smatch m;
      if (!std::regex_search(line, m, std::regex("^  (--?[a-z][a-z0-9-]*)"))) continue;
      CHECK(underHeading);
      CHECK(options.insert(m[1].str()).second);
    }
    CHECK(options.count("--help") == 1);
    bool grouped = false;
    for (const std::string& line : lines) grouped = grouped || headings.count(line) || line.rfind("decisions (", 0) == 0;
    CHECK(grouped);
  }
}

TEST_CASE("pack --help shows its own options on the first screen, run's options after its exit codes") {
  const e2e::CommandResult help = e2e::surrogate("pack --help");
  REQUIRE(help.exitCode == 0);
  const std::vector<std::string> lines = linesOf(help.output);
  std::size_t ownOutput = lines.size(), layout = lines.size(), runBlock = lines.size(), exclude = lines.size();
  for (std::size_t i = 0; i < lines.size(); ++i) {
    if (lines[i].rfind("  -o OUT ", 0) == 0) ownOutput = std::min(ownOutput, i);
    if (lines[i].rfind("  --layout ", 0) == 0) layout = std::min(layout, i);
    if (lines[i].rfind("the options of `surrogate run`", 0) == 0) runBlock = std::min(runBlock, i);
    if (lines[i].rfind("  --exclude ", 0) == 0) exclude = std::min(exclude, i);
  }
  INFO(help.output);
  CHECK(ownOutput < 25);  // the first screen
  CHECK(layout < 30);
  REQUIRE(runBlock < lines.size());
  CHECK(lineIndex(lines, "exit codes:") < runBlock);
  CHECK(runBlock < exclude);
  CHECK(exclude < lines.size());
}

TEST_CASE("quiet prints one summary line, the ordinary output folds long folders, verbose lists them") {
  const fs::path work = e2e::freshDir("cli-verbosity");
  const fs::path capture = e2e::smallCapture(work);
  // A tiled web copy: hundreds of tiles in a few folders.
  const std::string tiled = " --publish --publish-tiles deepzoom --publish-tile-size 32";

  const e2e::CommandResult quiet = e2e::surrogate("run " + e2e::quote(capture) + tiled + " --quiet");
  INFO(quiet.output);
  REQUIRE(quiet.exitCode == 0);
  const std::vector<std::string> quietLines = linesOf(quiet.output);
  REQUIRE(quietLines.size() == 1);
  CHECK(quietLines[0].rfind("Processed " + capture.string() + " (", 0) == 0);
  CHECK(quietLines[0].find("report: ") != std::string::npos);

  // Counted independently of the program: the files of the web copy's tile folders.
  std::size_t tiles = 0;
  for (const auto& e : fs::recursive_directory_iterator(capture / "finished-files" / "web"))
    tiles += e.is_regular_file() && e.path().extension() == ".jpg";
  REQUIRE(tiles > 3 * 8);

  const e2e::CommandResult normal = e2e::surrogate("run " + e2e::quote(capture));
  INFO(normal.output);
  REQUIRE(normal.exitCode == 0);
  const std::vector<std::string> normalLines = linesOf(normal.output);
  CHECK(normalLines.size() < 80);
  CHECK(std::regex_search(normal.output, std::regex("result: .*/finished-files/web/ \\([0-9]+ files; --verbose lists them\\)")));

  const e2e::CommandResult verbose = e2e::surrogate("run " + e2e::quote(capture) + " --verbose");
  REQUIRE(verbose.exitCode == 0);
  std::size_t listedTiles = 0;
  for (const std::string& line : linesOf(verbose.output))
    listedTiles += line.rfind("  result: ", 0) == 0 && line.size() > 4 && line.compare(line.size() - 4, 4, ".jpg") == 0;
  CHECK(listedTiles == tiles);

  const e2e::CommandResult both = e2e::surrogate("run " + e2e::quote(capture) + " --quiet --verbose");
  CHECK(both.exitCode == 2);
  CHECK_THAT(both.output, Catch::Contains("--verbose"));

  const fs::path package = work / "cap.zip";
  const e2e::CommandResult pack = e2e::surrogate("pack " + e2e::quote(capture) + " -o " + e2e::quote(package) + " --quiet");
  INFO(pack.output);
  REQUIRE(pack.exitCode == 0);
  REQUIRE(linesOf(pack.output).size() == 1);
  CHECK(std::regex_search(pack.output, std::regex("^Packed .* \\(package id urn:sha256:[0-9a-f]{64}\\)\\.\n$")));

  const e2e::CommandResult verify = e2e::surrogate("verify " + e2e::quote(package) + " --quiet");
  INFO(verify.output);
  REQUIRE(verify.exitCode == 0);
  REQUIRE(linesOf(verify.output).size() == 1);
  CHECK(verify.output.rfind("SOUND: ", 0) == 0);

  // A quiet verify of a damaged package still names what failed.
  const fs::path bag = work / "bag";
  REQUIRE(e2e::surrogate("pack " + e2e::quote(capture) + " -o " + e2e::quote(bag) + " --quiet").exitCode == 0);
  e2e::runShell("printf x >> " + e2e::quote(bag / "data" / "assembly-files" / "carrier.xml"));
  const e2e::CommandResult failed = e2e::surrogate("verify " + e2e::quote(bag) + " --quiet");
  INFO(failed.output);
  CHECK(failed.exitCode == 3);
  CHECK_THAT(failed.output, Catch::Contains("FAIL  "));
  CHECK_THAT(failed.output, Catch::Contains("NOT SOUND: "));
  CHECK(failed.output.find("  ok    ") == std::string::npos);
}

TEST_CASE("publish --json names the index page of a capture's models") {
  const fs::path work = e2e::freshDir("cli-publish-index");
  const fs::path capture = e2e::processedCapture(work);
  const e2e::CommandResult json = e2e::surrogate("publish " + e2e::quote(capture) + " -o " + e2e::quote(work / "web") + " --json");
  INFO(json.output);
  REQUIRE(json.exitCode == 0);
  CHECK_THAT(json.output, Catch::Contains("\"index\":\"index.html\""));
  CHECK(fs::is_regular_file(work / "web" / "index.html"));
  const e2e::CommandResult quiet = e2e::surrogate("publish " + e2e::quote(capture) + " -o " + e2e::quote(work / "web2") + " --quiet");
  REQUIRE(quiet.exitCode == 0);
  CHECK(linesOf(quiet.output).size() == 1);
}
