#include "cli/args.h"

#include <cctype>
#include <cmath>
#include <sstream>

#include "core/error.h"
#include "core/text.h"

namespace surrogate::cli {

namespace {
[[noreturn]] void usage(const std::string& option, const std::string& message) {
  throw Error(ErrorKind::Usage, option, "command line", message);
}
}  // namespace

Args::Args(int argc, char** argv, int first, std::vector<OptionSpec> specs) {
  for (int i = first; i < argc; ++i) {
    std::string arg = argv[i];
    if (arg == "--help" || arg == "-h") {
      help_ = true;
      continue;
    }
    // A one-letter option may be given with one dash, as people type it: -o FILE.
    if (arg.size() == 2 && arg[0] == '-' && std::isalpha(static_cast<unsigned char>(arg[1]))) {
      for (const OptionSpec& s : specs)
        if (s.name == arg.substr(1)) arg = "-" + arg;
    }
    if (arg.rfind("--", 0) != 0 || arg == "--") {
      positional_.push_back(arg);
      continue;
    }
    std::string name = arg.substr(2), value;
    bool inlineValue = false;
    if (const auto eq = name.find('='); eq != std::string::npos) {
      value = name.substr(eq + 1);
      name = name.substr(0, eq);
      inlineValue = true;
    }
    const OptionSpec* spec = nullptr;
    for (const OptionSpec& s : specs)
      if (s.name == name) spec = &s;
    if (!spec) {
      std::vector<std::string> names;
      for (const OptionSpec& s : specs) names.push_back(s.name);
      const auto near = nearestName(name, names);
      usage("--" + name, "is not an option of this command" +
                             (near ? "; did you mean --" + *near + "?" : std::string(" (see --help)")));
    }
    if (spec->takesValue && !inlineValue) {
      if (i + 1 >= argc) usage("--" + name, "needs a value: --" + name + " " + spec->valueName);
      value = argv[++i];
    } else if (!spec->takesValue && inlineValue) {
      usage("--" + name, "takes no value");
    }
    if (!spec->repeatable && values_.count(name))
      usage("--" + name, "is given twice; give it once");
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
  usage("--" + name, "needs a whole number, not \"" + *v + "\"");
}

double Args::doubleValue(const std::string& name, double fallback) const {
  const auto v = value(name);
  if (!v) return fallback;
  return parseNumberList(*v, 1, "--" + name)[0];
}

std::string Args::describe(const std::vector<OptionSpec>& specs) {
  std::ostringstream out;
  for (const OptionSpec& s : specs) {
    // One-letter options are written the way people type them: -o (--o is accepted too).
    std::string left = (s.name.size() == 1 ? "  -" : "  --") + s.name + (s.takesValue ? " " + s.valueName : "");
    if (left.size() < 30) left.resize(30, ' ');
    else left += "\n" + std::string(30, ' ');
    out << left << s.help << (s.repeatable ? " (repeatable)" : "") << "\n";
  }
  out << "  --help                      show this help\n";
  return out.str();
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
