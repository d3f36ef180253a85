// What the man page and completion tests read from the program itself: the commands
// `surrogate --help` lists and the options each command's --help lists, parsed here on their own
// (not with packaging/help's CMake parser), so that a generator that drops or garbles an option
// is caught.
#pragma once

#include <regex>
#include <sstream>
#include <string>
#include <vector>

#include "e2e_support.h"

namespace help_test {

inline std::vector<std::string> linesOf(const std::string& text) {
  std::vector<std::string> lines;
  std::istringstream in(text);
  for (std::string line; std::getline(in, line);) lines.push_back(line);
  return lines;
}

// A line without its leading spaces.
inline std::string trimmed(const std::string& line) {
  const std::size_t first = line.find_first_not_of(' ');
  return first == std::string::npos ? std::string() : line.substr(first);
}

// The commands under "commands:" in `surrogate --help`.
inline std::vector<std::string> commandNames() {
  const e2e::CommandResult top = e2e::surrogate("--help");
  std::vector<std::string> names;
  bool inCommands = false;
  for (const std::string& line : linesOf(top.output)) {
    std::smatch m;
    if (!line.empty() && line[0] != ' ') inCommands = line == "commands:";
    else if (inCommands && std::regex_match(line, m, std::regex("  ([a-z]+)  +.*"))) names.push_back(m[1].str());
  }
  return names;
}

// The text of `surrogate help NAME`.
inline std::string helpOf(const std::string& name) { return e2e::surrogate("help " + name).output; }

// The lines of a help text's section named `heading` ("examples:", "exit codes:"), up to the
// next blank line.
inline std::vector<std::string> sectionOf(const std::string& help, const std::string& heading) {
  std::vector<std::string> out;
  bool in = false;
  for (const std::string& line : linesOf(help)) {
    if (line == heading) in = true;
    else if (in && line.empty()) break;
    else if (in) out.push_back(line);
  }
  return out;
}

// Each option line's option ("--title", "-o") and the word after it ("TEXT"; empty for a flag),
// in order, outside the examples and exit codes.
inline std::vector<std::pair<std::string, std::string>> optionsOf(const std::string& help) {
  std::vector<std::pair<std::string, std::string>> out;
  std::string section;
  for (const std::string& line : linesOf(help)) {
    std::smatch m;
    if (!line.empty() && line[0] != ' ' && line.back() == ':') section = line;
    else if (section != "examples:" && section != "exit codes:" &&
             std::regex_match(line, m, std::regex("  (-[-A-Za-z0-9]*)(?: ([^ ]+))?(?:  .*)?")))
      out.emplace_back(m[1].str(), m[2].str());
  }
  return out;
}

}  // namespace help_test
