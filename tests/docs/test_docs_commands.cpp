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

// The capture the user guide starts from (docs/user-guide.md, "A capture to start with").
constexpr const char* kGeneratorOptions = "--out stela12 --images 12 --width 400 --height 300 --sphere-radius 45 --seed 7";

// A fresh folder with the generated capture as ./stela12 (12 shots, DNG originals + JPEG exports).
fs::path workFolder(const std::string& name) {
  const fs::path work = e2e::freshDir("docs-" + name);
  const e2e::CommandResult r =
      e2e::runShell("cd " + e2e::quote(work) + " && " + std::string(GENERATOR_EXE) + " " + kGeneratorOptions);
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

namespace {

// The member names of a JSON text, in order of appearance: every string followed by ':'
// outside another string (the output is one object, checked elsewhere to be valid JSON).
std::vector<std::string> jsonKeys(const std::string& json) {
  std::vector<std::string> keys;
  for (std::size_t i = 0; i < json.size(); ++i) {
    if (json[i] != '"') continue;
    std::string text;
    for (++i; i < json.size() && json[i] != '"'; ++i) {
      if (json[i] == '\\') ++i;
      else text += json[i];
    }
    std::size_t next = json.find_first_not_of(" \t\r\n", i + 1);
    if (next != std::string::npos && json[next] == ':') keys.push_back(text);
  }
  return keys;
}

// The text of the guide's section "### TITLE", up to the next heading.
std::string guideSection(const std::string& guide, const std::string& title) {
  const std::size_t start = guide.find("\n### " + title + "\n");
  if (start == std::string::npos) return "";
  const std::size_t end = guide.find("\n#", start + 1);
  return guide.substr(start, end == std::string::npos ? std::string::npos : end - start);
}

}  // namespace

TEST_CASE("every JSON member the commands print on the sample is documented in the user guide") {
  const std::string guide = slurp(fs::path(DOCS_DIR) / "user-guide.md");
  const fs::path work = workFolder("json");
  const std::string c = e2e::quote(work / "stela12");
  const std::string w = e2e::quote(work);
  std::ofstream(work / "list.txt") << (work / "p.tar").string() << "\n";  // for the batches
  // Runs whose output has every kind of member: a creator, an exclusion (decisions,
  // exclusions), a package, a verification with re-execution, an error.
  const std::vector<std::pair<std::string, std::string>> commands = {
      {"run " + c + " --creator \"Ana Silva:photographer\" --meta \"site=Store 3\" --exclude IMG_0003 "
       "--reason \"the flash did not fire\" --json", "run --json"},
      {"lights " + c + " -o " + w + "/l.lp --json", "lights --json"},
      {"fit --lp " + w + "/l.lp -o " + w + "/f.ptm --json", "fit --json"},
      {"render " + w + "/f.ptm --light 0.5,0,0.8 -o " + w + "/r.png --json", "render --json"},
      {"run " + c + " --quiet", ""},  // the capture's results again after `lights`
      {"publish " + c + " -o " + w + "/web --json", "publish --json"},
      {"info " + w + "/web/hsh2/info.json --json", "info --json"},
      {"pack " + c + " -o " + w + "/p.tar --json", "pack --json"},
      {"verify " + w + "/p.tar --reexecute --json", "verify --json"},
      {"report " + w + "/p.tar --verify -o " + w + "/r.html --json", "report --json"},
      {"batch " + w + "/list.txt -o " + w + "/l.jsonl --do verify --json", "batch --json"},
      {"batch --summary -o " + w + "/l.jsonl --json", "batch --json"},
      {"verify --batch " + w + "/list.txt -o " + w + "/a.jsonl --json", "verify --batch --json"},
      {"info " + c + " --json", "info --json"},
      {"info " + c + "/assembly-files/carrier.xml --json", "info --json"},
      {"info " + w + "/p.tar --json", "info --json"},
      {"info " + w + "/f.ptm --json", "info --json"},
      {"info " + c + "/finished-files/hsh2.rti --json", "info --json"},
      {"info " + w + "/l.lp --json", "info --json"},
      {"info " + c + "/original-captures/IMG_0001.dng --json", "info --json"},
      {"info " + c + "/jpeg-exports/IMG_0001.jpg --json", "info --json"},
      {"info " + w + "/nowhere.ptm --json", "Errors"},
  };
  for (const auto& [args, title] : commands) {
    const e2e::CommandResult r =
        e2e::runShell("(" + std::string(SURROGATE_EXE) + " " + args + " 2>/dev/null)");
    INFO("surrogate " << args << "\n" << r.output);
    if (title.empty()) {
      REQUIRE(r.exitCode == 0);
      continue;
    }
    CHECK((r.exitCode == 0) == (title != "Errors"));
    const std::string section = guideSection(guide, title);
    INFO("the guide's section \"### " << title << "\"");
    REQUIRE_FALSE(section.empty());
    const std::vector<std::string> keys = jsonKeys(r.output);
    CHECK(keys.size() >= 4);
    for (const std::string& key : keys) {
      // Documented as `key`, `key[]`, or within a path (`steps[].key`, `bagit.key`).
      INFO("the member \"" << key << "\"");
      CHECK(std::regex_search(section, std::regex("[`.]" + key + "(\\[\\])?[`.]")));
    }
  }
}

TEST_CASE("the user guide starts from the capture the docs test generates") {
  const std::string guide = slurp(fs::path(DOCS_DIR) / "user-guide.md");
  const std::size_t start = guide.find("## A capture to start with");
  REQUIRE(start != std::string::npos);
  // Nothing before it uses the capture; the generator's command there is the test's own.
  CHECK(guide.substr(0, start).find("stela12") == std::string::npos);
  const std::size_t generator = guide.find("build/samples/surrogate-generate " + std::string(kGeneratorOptions));
  CHECK(generator != std::string::npos);
  CHECK(generator > start);
  CHECK_THAT(guide, Catch::Contains("scripts/demo"));
}
