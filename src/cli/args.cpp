#include "cli/args.h"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <map>
#include <sstream>

#include "core/error.h"
#include "core/text.h"

namespace surrogate::cli {

namespace {
[[noreturn]] void usage(const std::string& option, const std::string& message) {
  throw Error(ErrorKind::Usage, option, "command line", message);
}

// What an unknown option most likely meant: for one letter, the long option people abbreviate
// that way (-q --quiet, -v --verbose) or the only one beginning with it; for a word given with
// one dash, the option of that name; else the nearest name within two letters (nearestName).
std::optional<std::string> suggestionFor(const std::string& name, const std::vector<OptionSpec>& specs) {
  std::vector<std::string> names;
  for (const OptionSpec& s : specs) names.push_back(s.name);
  const auto known = [&](const std::string& n) { return std::find(names.begin(), names.end(), n) != names.end(); };
  if (name.size() == 1) {
    static const std::map<char, std::string> usual = {{'q', "quiet"}, {'v', "verbose"}, {'j', "jobs"},
                                                      {'t', "threads"}, {'n', "dry-run"}};
    if (const auto it = usual.find(name[0]); it != usual.end() && known(it->second)) return it->second;
  } else if (known(name)) {
    return name;
  }
  return nearestName(name, names);
}

}  // namespace

// "-o" as people type a one-letter option, "--output" for the others.
std::string optionName(const std::string& name) { return name.size() == 1 ? "-" + name : "--" + name; }

Args::Args(int argc, char** argv, int first, std::vector<OptionSpec> specs) {
  bool optionsEnd = false;
  for (int i = first; i < argc; ++i) {
    const std::string arg = argv[i];
    if (optionsEnd) {
      positional_.push_back(arg);
      continue;
    }
    if (arg == "--help" || arg == "-h") {
      help_ = true;
      continue;
    }
    if (arg == "--") {  // what follows is positional, even a name that begins with a dash
      optionsEnd = true;
      continue;
    }
    // An option begins with a dash and a letter (-o, --output, -q); "-" alone (standard input)
    // and "-0.5" are not options.
    const bool doubleDash = arg.rfind("--", 0) == 0;
    const std::size_t letter = doubleDash ? 2 : 1;
    if (arg.size() <= letter || arg[0] != '-' || !std::isalpha(static_cast<unsigned char>(arg[letter]))) {
      positional_.push_back(arg);
      continue;
    }
    std::string name = arg.substr(letter), value;
    bool inlineValue = false;
    if (const auto eq = name.find('='); eq != std::string::npos) {
      value = name.substr(eq + 1);
      name = name.substr(0, eq);
      inlineValue = true;
    }
    const std::string typed = arg.substr(0, letter) + name;  // as given: -o, --o, --output
    const OptionSpec* spec = nullptr;
    // With one dash only a one-letter option: -quiet is not --quiet (it is suggested).
    for (const OptionSpec& s : specs)
      if (s.name == name && (doubleDash || name.size() == 1)) spec = &s;
    if (!spec) {
      const auto near = suggestionFor(name, specs);
      throw Error(ErrorKind::Usage, "", "command line",
                  "unknown option \"" + escapedText(typed) + "\"" +
                      (near ? ": did you mean " + optionName(*near) + "?"
                            : " (see --help)"));
    }
    if (spec->takesValue && !inlineValue) {
      if (i + 1 >= argc) usage(typed, "needs a value: " + typed + " " + spec->valueName);
      value = argv[++i];
    } else if (!spec->takesValue && inlineValue) {
      usage(typed, "takes no value");
    }
    if (!spec->repeatable && values_.count(name)) usage(typed, "is given twice; give it once");
    values_[name].push_back(value);
    ordered_.emplace_back(name, value);
  }
}

bool Args::has(const std::string& name) const { return values_.count(name) != 0; }

std::optional<std::string> Args::value(const std::string& name) const {
  auto it = values_.find(name);
  if (it == values_.end()) return std::nullopt;
  return it->second.back();
}

std::string Args::value(const std::string& name, const std::string& fallback) const {
  return value(name).value_or(fallback);
}

std::vector<std::string> Args::values(const std::string& name) const {
  auto it = values_.find(name);
  return it == values_.end() ? std::vector<std::string>{} : it->second;
}

int Args::intValue(const std::string& name, int fallback) const {
  const auto v = value(name);
  if (!v) return fallback;
  try {
    std::size_t used = 0;
    const int n = std::stoi(*v, &used);
    if (used == v->size()) return n;
  } catch (const std::exception&) {
  }
  usage(optionName(name), "needs a whole number, not \"" + *v + "\"");
}

double Args::doubleValue(const std::string& name, double fallback) const {
  const auto v = value(name);
  if (!v) return fallback;
  return parseNumberList(*v, 1, optionName(name))[0];
}

namespace {

// Breaks `text` into lines of at most `width` columns (a longer word stands alone), each after
// the first starting with `indent` spaces.
std::string wrapped(const std::string& text, std::size_t width, std::size_t indent, std::size_t firstColumn = 0) {
  std::string out, word;
  std::size_t column = firstColumn;
  std::istringstream words(text);
  bool first = true;
  while (words >> word) {
    if (!first && column + 1 + word.size() > width) {
      out += "\n" + std::string(indent, ' ');
      column = indent;
    } else if (!first) {
      out += ' ';
      ++column;
    }
    out += word;
    column += word.size();
    first = false;
  }
  return out;
}

std::string groupHeading(OptionGroup g) {
  switch (g) {
    case OptionGroup::Input: return "input";
    case OptionGroup::Description:
      return "description (recorded in the carrier's header; changing only these runs no step again)";
    case OptionGroup::Decisions:
      return "decisions (recorded with who, when and why; they stand for later runs until withdrawn)";
    case OptionGroup::Processing: return "processing";
    case OptionGroup::Output: return "output";
  }
  return "options";
}

constexpr std::size_t kHelpWidth = 100;  // columns: the help of an option is wrapped to fit
constexpr std::size_t kHelpColumn = 30;  // where an option's help starts

// The options of `specs` from `surrogate run` (fromRun) or not, under their group headings.
void describeGroups(std::ostringstream& out, const std::vector<OptionSpec>& specs, bool fromRun) {
  for (const OptionGroup g : {OptionGroup::Input, OptionGroup::Description, OptionGroup::Decisions,
                              OptionGroup::Processing, OptionGroup::Output}) {
    bool heading = false;
    for (const OptionSpec& s : specs) {
      if (s.group != g || s.fromRun != fromRun) continue;
      if (!heading) out << "\n" << groupHeading(g) << ":\n";
      heading = true;
      // One-letter options are written the way people type them: -o (--o is accepted too).
      std::string left = (s.name.size() == 1 ? "  -" : "  --") + s.name + (s.takesValue ? " " + s.valueName : "");
      if (left.size() < kHelpColumn) left.resize(kHelpColumn, ' ');
      else left += "\n" + std::string(kHelpColumn, ' ');
      out << left << wrapped(s.help + (s.repeatable ? " (repeatable)" : ""), kHelpWidth, kHelpColumn, kHelpColumn)
          << "\n";
    }
  }
}

}  // namespace

std::string Args::describe(const CommandHelp& help, const std::vector<OptionSpec>& specs) {
  std::ostringstream out;
  out << "usage: " << help.synopsis << "\n\n" << wrapped(help.description, kHelpWidth, 0) << "\n";
  describeGroups(out, specs, false);
  out << "  --help                      show this help\n";
  if (!help.examples.empty()) {
    out << "\nexamples:\n";
    for (const auto& [command, what] : help.examples)
      out << "  " << command << "\n      " << wrapped(what, kHelpWidth, 6, 6) << "\n";
  }
  if (!help.exitCodes.empty()) {
    out << "\nexit codes:\n";
    for (const auto& [code, meaning] : help.exitCodes)
      out << "  " << code << "  " << wrapped(meaning, kHelpWidth, 5, 5) << "\n";
  }
  // Last, after what the command is about: the long list it shares with `surrogate run`.
  if (std::any_of(specs.begin(), specs.end(), [](const OptionSpec& s) { return s.fromRun; })) {
    out << "\nthe options of `surrogate run`, for when the capture is processed first:\n";
    describeGroups(out, specs, true);
  }
  return out.str();
}

Verbosity verbosityOf(const Args& args) {
  if (args.has("quiet") && args.has("verbose"))
    usage("--verbose", "does not go with --quiet: give one of them");
  return args.has("quiet") ? Verbosity::Quiet : args.has("verbose") ? Verbosity::Verbose : Verbosity::Normal;
}

std::size_t parseByteSize(const std::string& text, const std::string& option) {
  if (text.empty()) usage(option, "needs a size such as 2G or 512M");
  double factor = 1;
  std::string number = text;
  switch (std::toupper(static_cast<unsigned char>(text.back()))) {
    case 'K': factor = 1024.0; number.pop_back(); break;
    case 'M': factor = 1024.0 * 1024; number.pop_back(); break;
    case 'G': factor = 1024.0 * 1024 * 1024; number.pop_back(); break;
    default: break;
  }
  const double v = parseNumberList(number, 1, option)[0] * factor;
  if (!(v >= 64.0 * 1024 * 1024))
    usage(option, "is too small: give at least 64M so that a band of rows fits");
  // Beyond 1 EiB no machine has the memory, and the number would not fit a size in bytes.
  if (v > 1024.0 * 1024 * 1024 * 1024 * 1024 * 1024)
    usage(option, "\"" + text + "\" is more memory than any machine has: give a size such as 2G or 512M");
  return static_cast<std::size_t>(v);
}

std::vector<double> parseNumberList(const std::string& text, std::size_t count,
                                    const std::string& option) {
  std::vector<double> out;
  std::stringstream ss(text);
  for (std::string item; std::getline(ss, item, ',');) {
    try {
      std::size_t used = 0;
      const double v = std::stod(item, &used);
      if (used != item.size() || !std::isfinite(v)) throw std::invalid_argument(item);
      out.push_back(v);
    } catch (const std::exception&) {
      usage(option, "needs numbers, not \"" + text + "\"");
    }
  }
  if (out.size() != count)
    usage(option, "needs " + std::to_string(count) + " comma-separated numbers, got \"" + text + "\"");
  return out;
}

}  // namespace surrogate::cli
