// The bash completion the build makes from --help (packaging/help), as bash runs it: sourced in a
// plain `bash --norc`, its function (the one `complete -p surrogate` names) called with
// COMP_WORDS and COMP_CWORD set as readline sets them, and with no PATH, so that it can only
// use bash's builtins.
#include <catch2/catch.hpp>

#include <fstream>
#include <set>

#include "e2e_support.h"
#include "help_support.h"

namespace fs = std::filesystem;
using Words = std::set<std::string>;

namespace {

const fs::path kCompletion = HELP_COMPLETION;

// What the completion offers for the command line `words` (the last being the word under the
// cursor, maybe empty), typed in folder `cwd`.
Words complete(const std::vector<std::string>& words, const fs::path& cwd = fs::temp_directory_path()) {
  static const fs::path driver = [] {
    const fs::path file = e2e::freshDir("completion-driver") / "complete.sh";
    std::ofstream(file) << "source \"$1\" || exit 3\n"
                           "spec=$(complete -p surrogate) || exit 4\n"
                           "f=${spec#*-F }; f=${f%% *}\n"
                           "shift\n"
                           "COMP_WORDS=(\"$@\"); COMP_CWORD=$(( $# - 1 ))\n"
                           "COMP_LINE=\"$*\"; COMP_POINT=${#COMP_LINE}\n"
                           "PATH=/nonexistent\n"
                           "\"$f\" surrogate \"${COMP_WORDS[COMP_CWORD]}\" \"${COMP_WORDS[COMP_CWORD-1]}\" || exit 5\n"
                           "printf '%s\\n' \"${COMPREPLY[@]}\"\n";
    return file;
  }();
  std::string command = "cd " + e2e::quote(cwd) + " && bash --norc --noprofile " + e2e::quote(driver) + " " +
                        e2e::quote(kCompletion);
  for (const std::string& word : words) command += " " + e2e::quote(word);
  const e2e::CommandResult r = e2e::runShell(command);
  INFO(command << "\n" << r.output);
  REQUIRE(r.exitCode == 0);
  Words offered;
  for (const std::string& line : help_test::linesOf(r.output))
    if (!line.empty()) offered.insert(line);
  return offered;
}

// The options (beginning with `prefix`) that `surrogate help NAME` lists.
Words optionsOf(const std::string& name, const std::string& prefix) {
  Words out;
  for (const auto& [option, value] : help_test::optionsOf(help_test::helpOf(name)))
    if (option.rfind(prefix, 0) == 0) out.insert(option);
  return out;
}

}  // namespace

TEST_CASE("the completion offers the commands after surrogate and after help") {
  CHECK(complete({"surrogate", "r"}) == Words{"run", "render", "report", "review"});
  CHECK(complete({"surrogate", "re"}) == Words{"render", "report", "review"});
  CHECK(complete({"surrogate", "help", "re"}) == Words{"render", "report", "review"});
  CHECK(complete({"surrogate", "--v"}) == Words{"--version"});
  const Words all = complete({"surrogate", ""});
  for (const std::string& name : help_test::commandNames()) {
    INFO(name);
    CHECK(all.count(name) == 1);
  }
  CHECK(all.count("help") == 1);
  CHECK(complete({"surrogate", "help", "run", ""}).empty());  // help takes one command
}

TEST_CASE("the completion offers the options of each command as its --help lists them") {
  CHECK(complete({"surrogate", "run", "--ti"}) == Words{"--title"});
  const Words pack = optionsOf("pack", "--");
  REQUIRE(pack.size() > 20);
  CHECK(complete({"surrogate", "pack", "--"}) == pack);
  for (const std::string& name : help_test::commandNames()) {
    INFO(name);
    const Words options = optionsOf(name, "-");
    REQUIRE(!options.empty());
    CHECK(complete({"surrogate", name, "capture", "-"}) == options);
  }
}

TEST_CASE("the completion offers files and folders for arguments and option values") {
  const fs::path dir = e2e::freshDir("completion-files");
  fs::create_directory(dir / "somefolder");
  std::ofstream(dir / "something.zip") << "x";
  std::ofstream(dir / "some file.lp") << "x";
  std::ofstream(dir / "other.txt") << "x";
  const Words some = {"./somefolder", "./something.zip", "./some file.lp"};
  CHECK(complete({"surrogate", "info", "./some"}, dir) == some);
  CHECK(complete({"surrogate", "info", "--json", "./some"}, dir) == some);  // a flag takes no value
  CHECK(complete({"surrogate", "run", "--lp", "./some"}, dir) == some);     // an option's value
  CHECK(complete({"surrogate", "verify", "oth"}, dir) == Words{"other.txt"});
}

TEST_CASE("the completion offers the choices of an option written as bag|ocfl|eark in its help") {
  // pack --help: "--layout bag|ocfl|eark".
  std::string layout;
  for (const auto& [option, value] : help_test::optionsOf(help_test::helpOf("pack")))
    if (option == "--layout") layout = value;
  REQUIRE(layout == "bag|ocfl|eark");
  CHECK(complete({"surrogate", "pack", "stela12", "--layout", ""}) == Words{"bag", "ocfl", "eark"});
  CHECK(complete({"surrogate", "pack", "stela12", "--layout", "o"}) == Words{"ocfl"});
}
