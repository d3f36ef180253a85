// Every command shown in the documentation runs: the ```sh blocks of docs/*.md are run in
// order, one document at a time, in a fresh folder holding a generated capture named stela12,
// with the built `surrogate` first on PATH; each command must exit with 0 (every subcommand is
// always built: no block is skipped). Other code blocks may show `surrogate ...` only as a
// synopsis (with CAPITAL placeholders or [options]), so no runnable-looking command escapes
// the test. And every option that a command's --help lists is documented in docs/user-guide.md.
#include <catch2/catch.hpp>

#include <algorithm>
#include <fstream>
#include <map>
#include <regex>
#include <sstream>

#include "e2e_support.h"

namespace fs = std::filesystem;

namespace {

struct Command {
  int line = 0;
  std::string text;
};

struct Block {
  fs::path file;
  int line = 0;             // of the opening fence
  std::string language;     // first word of the info string
  std::vector<Command> commands;  // continuation lines joined; comments and blanks dropped
};

std::vector<Block> codeBlocks(const fs::path& file) {
  std::ifstream in(file);
  std::vector<Block> blocks;
  std::string line;
  int number = 0;
  bool inside = false;
  std::string pending;
  int pendingLine = 0;
  while (std::getline(in, line)) {
    ++number;
    if (line.rfind("```", 0) == 0) {
      if (!inside) {
        Block b;
        b.file = file;
        b.line = number;
        const std::string info = line.substr(3);
        b.language = info.substr(0, info.find_first_of(" {"));
        blocks.push_back(b);
      }
      inside = !inside;
      continue;
    }
    if (!inside) continue;
    std::string text = line;
    while (!text.empty() && (text.back() == ' ' || text.back() == '\r')) text.pop_back();
    if (pending.empty()) pendingLine = number;
    if (!text.empty() && text.back() == '\\') {
      pending += text.substr(0, text.size() - 1) + " ";
      continue;
    }
    pending += text;
    const auto first = pending.find_first_not_of(' ');
    if (first != std::string::npos && pending[first] != '#')
      blocks.back().commands.push_back({pendingLine, pending.substr(first)});
    pending.clear();
  }
  return blocks;
}

std::vector<fs::path> docs() {
  std::vector<fs::path> out;
  for (const auto& e : fs::directory_iterator(DOCS_DIR))
    if (e.path().extension() == ".md") out.push_back(e.path());
  std::sort(out.begin(), out.end());
  return out;
}

// A fresh folder with the generated capture as ./stela12 (12 shots, DNG originals + JPEG exports).
fs::path workFolder(const std::string& name) {
  const fs::path work = e2e::freshDir("docs-" + name);
  const e2e::CommandResult r = e2e::runShell(std::string(GENERATOR_EXE) + " --out " + e2e::quote(work / "stela12") +
                                             " --images 12 --width 400 --height 300 --sphere-radius 45 --seed 7");
  if (r.exitCode != 0) FAIL("generator failed: " << r.output);
  fs::remove_all(work / "stela12/truth");
  return work;
}

std::string slurp(const fs::path& p) {
  std::ifstream f(p);
  std::ostringstream s;
  s << f.rdbuf();
  return s.str();
}

}  // namespace

TEST_CASE("every sh block of docs/*.md runs and exits with 0 on a generated capture") {
  const std::string bin = fs::path(SURROGATE_EXE).parent_path().string();
  int ran = 0;
  for (const fs::path& doc : docs()) {
    std::vector<Block> blocks = codeBlocks(doc);
    blocks.erase(std::remove_if(blocks.begin(), blocks.end(), [](const Block& b) { return b.language != "sh"; }),
                 blocks.end());
    if (blocks.empty()) continue;
    const fs::path work = workFolder(doc.stem().string());
    for (const Block& b : blocks) {
      for (const Command& c : b.commands) {
        const e2e::CommandResult r = e2e::runShell("cd " + e2e::quote(work) + " && PATH=" + e2e::quote(bin) +
                                                   ":\"$PATH\" " + c.text);
        INFO(doc.filename().string() << ":" << c.line << ": " << c.text << "\n" << r.output);
        CHECK(r.exitCode == 0);
        ++ran;
      }
    }
  }
  CHECK(ran >= 20);  // the guide's walk-through and reference alone have more
}

TEST_CASE("outside sh blocks, docs show surrogate commands only as synopses") {
  // A synopsis has a placeholder in capitals (CAPTURE, FILE.lp, OUT) or [options].
  const std::regex placeholder("\\b[A-Z][A-Z_]{2,}\\b|\\[");
  for (const fs::path& doc : docs()) {
    for (const Block& b : codeBlocks(doc)) {
      if (b.language == "sh") continue;
      for (const Command& c : b.commands) {
        if (!std::regex_search(c.text, std::regex("^surrogate [a-z]"))) continue;  // a subcommand
        INFO(doc.filename().string() << ":" << c.line << ": " << c.text
                                     << "\n(put runnable commands in a ```sh block: tests/docs runs them)");
        CHECK(std::regex_search(c.text, placeholder));
      }
    }
  }
}

TEST_CASE("the user guide documents every command and every option their --help lists") {
  const std::string guide = slurp(fs::path(DOCS_DIR) / "user-guide.md");
  const e2e::CommandResult top = e2e::surrogate("--help");
  REQUIRE(top.exitCode == 0);
  std::vector<std::string> commands;
  std::istringstream lines(top.output.substr(top.output.find("commands:")));
  for (std::string line; std::getline(lines, line);) {
    std::smatch m;
    if (std::regex_match(line, m, std::regex("  ([a-z]+) +.*"))) commands.push_back(m[1].str());
  }
  REQUIRE(commands.size() >= 6);
  for (const std::string& command : commands) {
    INFO("surrogate " << command);
    CHECK(guide.find("### surrogate " + command) != std::string::npos);
    const e2e::CommandResult help = e2e::surrogate(command + " --help");
    REQUIRE(help.exitCode == 0);
    std::istringstream options(help.output);
    for (std::string line; std::getline(options, line);) {
      std::smatch m;
      if (!std::regex_search(line, m, std::regex("^  (--?[a-z][a-z0-9-]*)"))) continue;
      const std::string option = m[1].str();
      if (option == "--help") continue;
      INFO(option << " (from: " << line << ")");
      CHECK(guide.find("`" + option) != std::string::npos);
    }
  }
}
