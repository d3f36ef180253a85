// The man page generator (packaging/help/man_page.cmake) on help text that roff would misread:
// backslashes, lines beginning with '.' or "'", options with hyphens inside their names. It is
// run on a stand-in program printing that text, and the page must show the text as written,
// without a groff warning, its option names as \- (so that `man` searches find them).
#include <catch2/catch.hpp>

#include <fstream>

#include "e2e_support.h"
#include "help_support.h"

namespace fs = std::filesystem;

namespace {

const char* const kTopHelp =
    "surrogate 1.0: a stand-in\n"
    "\n"
    "usage: surrogate COMMAND [options]\n"
    "\n"
    "commands:\n"
    "  odd       a command with a \\ backslash; and brackets [x\n"
    "\n"
    "exit codes: 0 success, 1 bad input, 2 bad usage\n";

const char* const kOddHelp =
    "usage: surrogate odd FILE [options]\n"
    "\n"
    "A paragraph with \\n and \\fB not bold, and a line that\n"
    ".starts with a dot\n"
    "'and one with a quote; and --an-option in it.\n"
    "\n"
    "input:\n"
    "  --weird-name VALUE          read from C:\\path\\to and \\\\server\n"
    "                              .continued with a dot [unbalanced\n"
    "  -x                          a flag\n"
    "\n"
    "examples:\n"
    "  surrogate odd 'a\\b' --weird-name -0.5\n"
    "      what it does\n"
    "  surrogate odd .hidden -x\n"
    "\n"
    "exit codes:\n"
    "  0  fine\n"
    "  1  bad input\n";

// `text`'s lines as one line, without indents and with runs of spaces as one.
std::string flattened(const std::string& text) {
  std::string out;
  for (const std::string& line : help_test::linesOf(text))
    for (const char c : help_test::trimmed(line) + " ")
      if (c != ' ' || out.empty() || out.back() != ' ') out += c;  // runs of spaces as one
  return out;
}

}  // namespace

TEST_CASE("help text roff would misread reaches the man page as written") {
  const fs::path dir = e2e::freshDir("help-roff");
  std::ofstream(dir / "top.txt") << kTopHelp;
  std::ofstream(dir / "odd.txt") << kOddHelp;
  {
    std::ofstream program(dir / "stand-in");
    program << "#!/bin/sh\ncase \"$1 $2\" in\n"
               "  '--help ') cat '" << (dir / "top.txt").string() << "' ;;\n"
               "  'help odd') cat '" << (dir / "odd.txt").string() << "' ;;\n"
               "  *) exit 2 ;;\nesac\n";
  }
  fs::permissions(dir / "stand-in", fs::perms::owner_all);
  const e2e::CommandResult made = e2e::runShell(
      e2e::quote(CMAKE_COMMAND) + " -DSURROGATE=" + e2e::quote(dir / "stand-in") + " -DVERSION=1.0 -DGZIP=gzip -DOUT=" +
      e2e::quote(dir / "out") + " -P " + e2e::quote(HELP_SCRIPT));
  INFO(made.output);
  REQUIRE(made.exitCode == 0);

  const fs::path page = dir / "out" / "man1" / "surrogate-odd.1.gz";
  const std::string roff = e2e::bytesOf(dir / "out" / "roff" / "surrogate-odd.1");
  CHECK(roff.find("\\fB\\-\\-weird\\-name\\fR \\fIVALUE\\fR") != std::string::npos);
  CHECK(roff.find("and \\-\\-an\\-option in it") != std::string::npos);

  for (const fs::path& p : {page, dir / "out" / "man1" / "surrogate.1.gz"}) {
    const e2e::CommandResult warnings = e2e::runShell(
        "(LC_ALL=C.UTF-8 MANROFFSEQ='' MANWIDTH=80 man --warnings -E UTF-8 -l -Tutf8 -Z " + e2e::quote(p) +
        " >/dev/null)");
    INFO(p.filename().string());
    CHECK(warnings.exitCode == 0);
    CHECK(warnings.output == "");
  }
  const e2e::CommandResult shown =
      e2e::runShell("(LC_ALL=C.UTF-8 MANWIDTH=200 MANPAGER=cat man -E UTF-8 -l " + e2e::quote(page) + " 2>/dev/null)");
  const std::string text = flattened(shown.output);
  INFO(shown.output);
  CHECK(text.find("A paragraph with \\n and \\fB not bold, and a line that .starts with a dot "
                  "'and one with a quote; and --an-option in it.") != std::string::npos);
  CHECK(text.find("--weird-name VALUE") != std::string::npos);
  CHECK(text.find("read from C:\\path\\to and \\\\server .continued with a dot [unbalanced") != std::string::npos);
  CHECK(text.find("surrogate odd 'a\\b' --weird-name -0.5") != std::string::npos);
  CHECK(text.find("surrogate odd .hidden -x") != std::string::npos);

  const std::string top = flattened(
      e2e::runShell("(LC_ALL=C.UTF-8 MANWIDTH=200 MANPAGER=cat man -E UTF-8 -l " +
                    e2e::quote(dir / "out" / "man1" / "surrogate.1.gz") + " 2>/dev/null)")
          .output);
  CHECK(top.find("odd a command with a \\ backslash; and brackets [x") != std::string::npos);
  CHECK(top.find("surrogate-odd(1)") != std::string::npos);
}
