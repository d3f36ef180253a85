// Progress as a user sees it: every step of a run, a pack and a re-execution moves its bar in
// order to 100 %, read through SURROGATE_PROGRESS=lines ("progress<TAB>PERCENT<TAB>LABEL");
// and on a narrow terminal a label is shortened at a word boundary, never cut inside a word.
#include <catch2/catch.hpp>

#include <map>
#include <regex>
#include <set>
#include <sstream>

#include "cli/progress.h"
#include "e2e_support.h"

namespace fs = std::filesystem;
using surrogate::cli::fitLabel;

namespace {

struct Part {
  std::string label;
  std::vector<int> percents;
};

// The progress lines of a command's output, grouped into runs of one label, in order.
std::vector<Part> progressParts(const std::string& output) {
  std::vector<Part> parts;
  std::istringstream in(output);
  const std::regex line("progress\t([0-9]+)\t(.+)");
  for (std::string text; std::getline(in, text);) {
    std::smatch m;
    if (!std::regex_match(text, m, line)) continue;
    if (parts.empty() || parts.back().label != m[2].str()) parts.push_back({m[2].str(), {}});
    parts.back().percents.push_back(std::stoi(m[1].str()));
  }
  return parts;
}

e2e::CommandResult withProgressLines(const std::string& args) {
  return e2e::runShell("SURROGATE_PROGRESS=lines " + std::string(SURROGATE_EXE) + " " + args);
}

// Every label shows up once, with at least two values, increasing, the last 100; the labels
// `expected` are among them. Returns the labels seen.
std::set<std::string> checkParts(const e2e::CommandResult& r, const std::vector<std::string>& expected) {
  INFO(r.output);
  REQUIRE(r.exitCode == 0);
  const std::vector<Part> parts = progressParts(r.output);
  std::set<std::string> seen;
  for (const Part& p : parts) {
    std::ostringstream values;
    for (int v : p.percents) values << v << " ";
    INFO("label \"" << p.label << "\": " << values.str());
    CHECK(seen.insert(p.label).second);  // one part after another, never back to an earlier one
    CHECK(p.percents.size() >= 2);
    for (std::size_t i = 1; i < p.percents.size(); ++i) CHECK(p.percents[i] > p.percents[i - 1]);
    CHECK(p.percents.back() == 100);
  }
  for (const std::string& label : expected) {
    INFO("expected the label \"" << label << "\"");
    CHECK(seen.count(label) == 1);
  }
  return seen;
}

}  // namespace

TEST_CASE("a label that does not fit is shortened after a whole word with an ellipsis") {
  const std::string label = "re-executing: Hashing and reading metadata";
  CHECK(fitLabel(label, 60) == label);
  CHECK(fitLabel(label, static_cast<int>(label.size())) == label);
  CHECK(fitLabel(label, 32) == "re-executing: Hashing and\u2026");
  CHECK(fitLabel("Highlight detection", 18) == "Highlight\u2026");
  CHECK(fitLabel("re-executing: Normals, albedo and previews", 24) == "re-executing: Normals\u2026");
  // Not even the first word fits: the ellipsis alone rather than a piece of a word.
  CHECK(fitLabel("extracting for re-execution", 8) == "\u2026");
  CHECK(fitLabel("reading stela12-package.zip", 12) == "reading\u2026");
}

TEST_CASE("every step of a 24-image run moves its progress in order to 100 percent") {
  const fs::path work = e2e::freshDir("progress-steps");
  const fs::path capture = e2e::smallCapture(work, 24);
  checkParts(withProgressLines("run " + e2e::quote(capture)),
             {"Hashing and reading metadata", "Decoding images", "Sphere detection", "Highlight detection",
              "Fitting ptm-lrgb", "Fitting hsh2", "Normals, albedo and previews", "Writing the report"});

  const fs::path package = work / "stela24.zip";
  checkParts(withProgressLines("pack " + e2e::quote(capture) + " -o " + e2e::quote(package)), {"packing"});

  checkParts(withProgressLines("verify " + e2e::quote(package) + " --reexecute"),
             {"reading stela24.zip", "extracting for re-execution", "re-executing: Hashing and reading metadata",
              "re-executing: Decoding images", "re-executing: Sphere detection",
              "re-executing: Highlight detection", "re-executing: Fitting ptm-lrgb",
              "re-executing: Fitting hsh2", "re-executing: Normals, albedo and previews"});

  const e2e::CommandResult report = withProgressLines("report " + e2e::quote(package) + " -o " +
                                                      e2e::quote(work / "report.html"));
  checkParts(report, {"reading stela24.zip", "extracting the pictures", "Writing the report"});
}

TEST_CASE("progress lines are not printed without SURROGATE_PROGRESS or with --quiet") {
  const fs::path capture = e2e::smallCapture(e2e::freshDir("progress-quiet"));
  const e2e::CommandResult plain = e2e::surrogate("run " + e2e::quote(capture));  // stderr is a pipe
  REQUIRE(plain.exitCode == 0);
  CHECK(progressParts(plain.output).empty());
  const e2e::CommandResult quiet = withProgressLines("run " + e2e::quote(capture) + " --quiet");
  REQUIRE(quiet.exitCode == 0);
  CHECK(progressParts(quiet.output).empty());
}

TEST_CASE("on a narrow terminal progress labels are shortened at word boundaries and fit the width") {
  const fs::path work = e2e::freshDir("progress-narrow");
  const fs::path capture = e2e::smallCapture(work);
  const fs::path package = work / "bag.tar";
  REQUIRE(e2e::surrogate("pack " + e2e::quote(capture) + " -o " + e2e::quote(package) + " --quiet").exitCode == 0);
  // The labels the command reports, whole.
  std::set<std::string> labels;
  for (const Part& p : progressParts(withProgressLines("verify " + e2e::quote(package) + " --reexecute").output))
    labels.insert(p.label);
  REQUIRE(labels.count("re-executing: Normals, albedo and previews") == 1);

  // script(1) gives a terminal of no known size: the width comes from COLUMNS.
  constexpr int kColumns = 40;
  const e2e::CommandResult r = e2e::runShell(
      "COLUMNS=" + std::to_string(kColumns) + " script -qec " +
      e2e::quote(std::string(SURROGATE_EXE) + " verify " + e2e::quote(package) + " --reexecute") + " /dev/null");
  INFO(r.output);
  REQUIRE(r.exitCode == 0);
  const std::regex bar("(.*?) *\\[[# ]+\\] +([0-9]+)%");
  int bars = 0, shortened = 0;
  std::string text = r.output;
  for (char& c : text)
    if (c == '\r') c = '\n';
  std::istringstream in(text);
  for (std::string drawn; std::getline(in, drawn);) {
    std::smatch m;
    if (!std::regex_match(drawn, m, bar)) continue;
    ++bars;
    INFO("drawn: \"" << drawn << "\"");
    const std::string shown = m[1].str();
    CHECK(std::count_if(drawn.begin(), drawn.end(), [](char c) { return (c & 0xC0) != 0x80; }) < kColumns);
    if (labels.count(shown)) continue;
    ++shortened;
    const std::string ellipsis = "\u2026";
    REQUIRE(shown.size() >= ellipsis.size());
    REQUIRE(shown.compare(shown.size() - ellipsis.size(), ellipsis.size(), ellipsis) == 0);
    const std::string kept = shown.substr(0, shown.size() - ellipsis.size());
    // What is kept is the start of a label, ending where a word ends (before a space, or the
    // punctuation before one).
    bool wordPrefix = false;
    for (const std::string& label : labels) {
      if (label.compare(0, kept.size(), kept) != 0 || label.size() <= kept.size()) continue;
      const std::string rest = label.substr(kept.size());
      wordPrefix = wordPrefix || std::regex_search(rest, std::regex("^[,;:]? "));
    }
    CHECK(wordPrefix);
  }
  CHECK(bars > 10);
  CHECK(shortened > 0);  // the long labels did not fit in 40 columns
}
