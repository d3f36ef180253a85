// A small command-line parser: positional arguments and --options, each option declared with
// whether it takes a value and whether it may repeat. Unknown or malformed options are usage
// errors (exit code 2) that name the option.
#pragma once

#include <map>
#include <optional>
#include <string>
#include <vector>

namespace surrogate::cli {

// The headings a command's --help groups its options under, in this order.
enum class OptionGroup {
  Input,        // what is read, and how
  Description,  // the capture's descriptive metadata (title, creators, rights): no step reruns
  Decisions,    // standing decisions recorded with who, when and why
  Processing,   // parameters of the processing, and how it runs (threads, memory)
  Output,       // what is written or printed
};

struct OptionSpec {
  std::string name;  // without the leading "--"
  bool takesValue = true;
  bool repeatable = false;
  std::string help;  // one line, for --help
  std::string valueName = "VALUE";
  OptionGroup group = OptionGroup::Processing;
  // An option of `surrogate run` that another command (pack, lights, audit) also takes: its
  // --help lists it after the command's own options.
  bool fromRun = false;
};

// What a command's --help says: its synopsis, a paragraph, its options (grouped, its own
// first), two examples and its exit codes.
struct CommandHelp {
  std::string synopsis;     // "surrogate pack CAPTURE -o OUT [options]"
  std::string description;  // one paragraph, wrapped when printed
  std::vector<std::pair<std::string, std::string>> examples;  // command line, what it does
  std::vector<std::pair<int, std::string>> exitCodes;        // code, meaning
};

class Args {
 public:
  // Parses argv[first..argc) against `specs`. `--help` is always
  // accepted; a one-letter option may be written -o as well as --o. Anything else beginning with
  // a dash and a letter is an option: an unknown one is a usage error naming it as typed, with
  // the option it most likely meant ("unknown option \"-q\": did you mean --quiet?"). After
  // "--" every argument is positional.
  Args(int argc, char** argv, int first, std::vector<OptionSpec> specs);

  bool helpRequested() const { return help_; }
  const std::vector<std::string>& positional() const { return positional_; }
  bool has(const std::string& name) const;
  std::optional<std::string> value(const std::string& name) const;
  std::string value(const std::string& name, const std::string& fallback) const;
  std::vector<std::string> values(const std::string& name) const;
  // Options in the order given, for options whose meaning depends on order (--exclude X
  // --reason Y).
  const std::vector<std::pair<std::string, std::string>>& ordered() const { return ordered_; }
  int intValue(const std::string& name, int fallback) const;
  double doubleValue(const std::string& name, double fallback) const;

  // A command's whole --help: usage, description, its own options grouped under headings,
  // examples, exit codes, and last the options it shares with `surrogate run`, grouped too.
  static std::string describe(const CommandHelp& help, const std::vector<OptionSpec>& specs);

 private:
  bool help_ = false;
  std::vector<std::string> positional_;
  std::vector<std::pair<std::string, std::string>> ordered_;
  std::map<std::string, std::vector<std::string>> values_;
};

// An option's name as a person types it and as the carrier records it: "-o" for a one-letter
// option, "--output" for the others (never "--o").
std::string optionName(const std::string& name);

// How much a command prints: --quiet (at most a summary line), --verbose (every file and
// warning), or neither. Both together are a usage error.
enum class Verbosity { Quiet, Normal, Verbose };
Verbosity verbosityOf(const Args& args);

// Parses "1.5G", "512M", "2048" (bytes) for --memory.
std::size_t parseByteSize(const std::string& text, const std::string& option);
// Parses "a,b,c" numbers for --light x,y,z, --sphere cx,cy,r, --sphere-roi x,y,w,h.
std::vector<double> parseNumberList(const std::string& text, std::size_t count,
                                    const std::string& option);

}  // namespace surrogate::cli
