// The man pages the build makes from --help (packaging/help): one per command and surrogate.1,
// compressed as Debian policy asks, each rendered as lintian renders it (`man --warnings ... -Z`)
// without a warning, and showing every option, example and exit code its command's --help gives;
// dated by SOURCE_DATE_EPOCH or the version's date, never the build's, so two builds make the same bytes.
#include <catch2/catch.hpp>

#include <cstdlib>
#include <ctime>
#include <filesystem>
#include <set>

#include "e2e_support.h"
#include "help_support.h"

namespace fs = std::filesystem;
using help_test::linesOf;
using help_test::trimmed;

namespace {

const fs::path kPages = HELP_PAGES_DIR;

// What groff says about `page` when lintian formats it: its warnings (standard error) only.
std::string manWarnings(const fs::path& page) {
  const e2e::CommandResult r = e2e::runShell(
      "(LC_ALL=C.UTF-8 MANROFFSEQ='' MANWIDTH=80 man --warnings -E UTF-8 -l -Tutf8 -Z " +
      e2e::quote(page) + " >/dev/null)");
  return r.exitCode == 0 ? r.output : "man failed (" + std::to_string(r.exitCode) + "): " + r.output;
}

// `page` as `man` shows it on an 80-column terminal, each line without its indent, minus signs
// as the '-' a user types.
std::vector<std::string> rendered(const fs::path& page) {
  const e2e::CommandResult r = e2e::runShell(
      "(LC_ALL=C.UTF-8 MANWIDTH=80 MANPAGER=cat PAGER=cat man -E UTF-8 -l " + e2e::quote(page) +
      " 2>/dev/null)");
  std::string text = r.output;
  for (const std::string minus : {"\u2212", "\u2010"})
    for (std::size_t at; (at = text.find(minus)) != std::string::npos;) text.replace(at, minus.size(), "-");
  std::vector<std::string> lines;
  for (const std::string& line : linesOf(text)) lines.push_back(trimmed(line));
  return lines;
}

// Whether a line of `lines` begins with `start` followed by a space or nothing (a .TP tag).
bool hasLineStarting(const std::vector<std::string>& lines, const std::string& start) {
  for (const std::string& line : lines)
    if (line.rfind(start, 0) == 0 && (line.size() == start.size() || line[start.size()] == ' ')) return true;
  return false;
}

bool hasLine(const std::vector<std::string>& lines, const std::string& wanted) {
  for (const std::string& line : lines)
    if (line == wanted) return true;
  return false;
}

std::string joined(const std::vector<std::string>& lines) {
  std::string all;
  for (const std::string& line : lines) all += line + "\n";
  return all;
}

}  // namespace

TEST_CASE("every command has a man page that man formats without a warning") {
  REQUIRE(e2e::runShell("command -v man groff").exitCode == 0);  // man-db and groff-base
  const std::vector<std::string> names = help_test::commandNames();
  REQUIRE(names.size() >= 12);
  std::set<std::string> expected = {"surrogate.1.gz"}, found;
  for (const std::string& name : names) expected.insert("surrogate-" + name + ".1.gz");
  for (const auto& entry : fs::directory_iterator(kPages)) found.insert(entry.path().filename().string());
  CHECK(found == expected);  // and no page of a command that is gone
  for (const std::string& page : expected) {
    INFO(page);
    REQUIRE(fs::is_regular_file(kPages / page));
    CHECK(manWarnings(kPages / page) == "");
  }
}

TEST_CASE("each command page shows every option, example and exit code of its help") {
  for (const std::string& name : help_test::commandNames()) {
    INFO("surrogate-" << name << ".1.gz");
    const std::string help = help_test::helpOf(name);
    const std::vector<std::string> page = rendered(kPages / ("surrogate-" + name + ".1.gz"));
    REQUIRE(page.size() > 20);
    // The NAME line `whatis` and `man -k` read, and the usage.
    CHECK(hasLineStarting(page, "surrogate-" + name + " -"));
    CHECK(joined(page).find("SYNOPSIS\nsurrogate " + name) != std::string::npos);
    const auto options = help_test::optionsOf(help);
    REQUIRE(options.size() >= 4);  // at least --quiet, --verbose, --json, --help
    for (const auto& [option, value] : options) {
      INFO(option << " " << value);
      CHECK(hasLineStarting(page, value.empty() ? option : option + " " + value));
    }
    for (const std::string& line : help_test::sectionOf(help, "examples:"))
      if (line.rfind("  surrogate ", 0) == 0) CHECK(hasLine(page, trimmed(line)));
    const std::vector<std::string> codes = help_test::sectionOf(help, "exit codes:");
    REQUIRE(!codes.empty());
    for (const std::string& line : codes)
      if (line.size() > 3 && line[2] != ' ') CHECK(hasLineStarting(page, line.substr(2, line.find(' ', 2) - 2)));
  }
}

TEST_CASE("surrogate.1 lists the commands, exit codes, data folder and environment") {
  const std::vector<std::string> page = rendered(kPages / "surrogate.1.gz");
  const std::string text = joined(page);
  CHECK(hasLineStarting(page, "surrogate - digital surrogates"));
  for (const std::string& name : help_test::commandNames()) {
    INFO(name);
    CHECK(hasLineStarting(page, name));
    CHECK(text.find("surrogate-" + name + "(1)") != std::string::npos);  // SEE ALSO
  }
  for (const std::string code : {"0", "1", "2", "3", "4", "5"}) CHECK(hasLineStarting(page, code));
  for (const std::string section : {"COMMANDS", "EXIT STATUS", "FILES", "ENVIRONMENT", "SEE ALSO"})
    CHECK(hasLine(page, section));
  CHECK(text.find("/usr/share/surrogate") != std::string::npos);
  CHECK(hasLine(page, "SURROGATE_RESOURCES"));
}

TEST_CASE("the pages are gzip -9n: best compression, no name or time stored") {
  for (const auto& entry : fs::directory_iterator(kPages)) {
    INFO(entry.path().filename().string());
    const std::string bytes = e2e::bytesOf(entry.path());
    REQUIRE(bytes.size() > 18);
    CHECK(static_cast<unsigned char>(bytes[0]) == 0x1f);
    CHECK(static_cast<unsigned char>(bytes[1]) == 0x8b);
    CHECK((bytes[3] & 0x08) == 0);          // FNAME: no file name
    CHECK(bytes.substr(4, 4) == std::string(4, '\0'));  // MTIME: none
    CHECK(bytes[8] == 2);                   // XFL 2: compressed with the slowest, best level
  }
}

TEST_CASE("the pages are dated by SOURCE_DATE_EPOCH or the release date only and are the same bytes twice") {
  const fs::path dir = e2e::freshDir("help-pages-twice");
  const auto generate = [&](const std::string& out, const std::string& env) {
    return e2e::runShell(env + " " + e2e::quote(CMAKE_COMMAND) + " -DSURROGATE=" + e2e::quote(SURROGATE_EXE) +
                         " -DVERSION=9.8.7 -DGZIP=gzip -DOUT=" + e2e::quote(dir / out) + " -P " +
                         e2e::quote(HELP_SCRIPT));
  };
  REQUIRE(generate("a", "SOURCE_DATE_EPOCH=1700000000").exitCode == 0);
  REQUIRE(generate("b", "SOURCE_DATE_EPOCH=1700000000").exitCode == 0);
  REQUIRE(generate("c", "env -u SOURCE_DATE_EPOCH").exitCode == 0);
  // The version's date (packaging/CMakeLists.txt passes SURROGATE_RELEASE_DATE).
  REQUIRE(e2e::runShell("env -u SOURCE_DATE_EPOCH " + e2e::quote(CMAKE_COMMAND) + " -DSURROGATE=" +
                        e2e::quote(SURROGATE_EXE) + " -DVERSION=9.8.7 -DRELEASE_DATE=2025-01-02 -DGZIP=gzip -DOUT=" +
                        e2e::quote(dir / "d") + " -P " + e2e::quote(HELP_SCRIPT))
              .exitCode == 0);
  CHECK(e2e::bytesOf(dir / "d" / "roff" / "surrogate-pack.1").find(".TH SURROGATE-PACK 1 \"2025-01-02\"") !=
        std::string::npos);
  std::size_t compared = 0;
  for (const auto& entry : fs::directory_iterator(dir / "a" / "man1")) {
    INFO(entry.path().filename().string());
    CHECK(e2e::bytesOf(entry.path()) == e2e::bytesOf(dir / "b" / "man1" / entry.path().filename()));
    ++compared;
  }
  CHECK(compared >= 13);
  const std::string dated = e2e::bytesOf(dir / "a" / "roff" / "surrogate-run.1");
  CHECK(dated.find(".TH SURROGATE-RUN 1 \"2023-11-14\" \"Surrogate 9.8.7\"") != std::string::npos);
  // Without either, no date at all: never the day of the build.
  char today[16];
  const std::time_t now = std::time(nullptr);
  std::strftime(today, sizeof today, "%Y-%m-%d", std::gmtime(&now));
  const std::string undated = e2e::bytesOf(dir / "c" / "roff" / "surrogate.1");
  CHECK(undated.find(".TH SURROGATE 1 \"\" \"Surrogate 9.8.7\"") != std::string::npos);
  CHECK(undated.find(today) == std::string::npos);
}
