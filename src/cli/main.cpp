// surrogate: the command-line tool. Dispatches to a subcommand and turns errors into a
// message naming the file and an exit code:
//   0 success (verify: the package is sound)
//   1 bad input: a capture, image or file that cannot be processed
//   2 bad usage (options), or an invalid package
//   3 fixity failure (verify)
//   4 not reproduced (verify --reexecute)
//   5 internal error (a bug, or the environment: disk full); a data file missing from the
//     installation is exit 1 (core/resources.h)
#include <csignal>
#include <exception>
#include <iostream>
#include <string>
#include <vector>

#include "cli/commands.h"
#include "cli/version_text.h"
#include "core/error.h"
#include "core/json.h"
#include "core/resident.h"
#include "core/resources.h"
#include "core/text.h"
#include "core/version.h"

using namespace surrogate;

namespace {
void printUsage() {
  std::cout << "surrogate " << surrogateVersion()
            << ": digital surrogates of Highlight-RTI captures, with their provenance\n\n"
               "usage: surrogate COMMAND [options]    (surrogate help COMMAND, or surrogate COMMAND --help,\n"
               "                                      for details)\n\n"
               "commands:\n";
  for (const cli::Command& c : cli::commands()) {
    std::string name = c.name;
    name.resize(10, ' ');
    std::cout << "  " << name << c.summary << "\n";
  }
  std::cout << "\nexit codes: 0 success, 1 bad input, 2 bad usage or invalid package, "
               "3 fixity failure, 4 not reproduced, 5 internal error\n";
}

// With --json, a failure is also one JSON object on stdout, so a script reading stdout always
// gets JSON: {"error":{"exitCode":1,"file":"...","step":"...","message":"..."}}.
int fail(bool json, const std::string& command, int exitCode, const std::string& file,
         const std::string& step, const std::string& message, const std::string& text) {
  // Names and values from files reach the message: never raw control bytes to the terminal.
  std::cerr << "surrogate " << command << ": " << escapedText(text, true) << "\n";
  if (json) {
    JsonWriter j;
    j.beginObject().key("error").beginObject().key("exitCode").value(exitCode).key("file").value(file)
        .key("step").value(step).key("message").value(message).endObject().endObject();
    std::cout << j.str() << "\n";
  }
  return exitCode;
}

// "run, pack, lights, ...": the commands, for a message about an unknown one.
std::string commandNames() {
  std::string names;
  for (const cli::Command& c : cli::commands()) names += (names.empty() ? "" : ", ") + std::string(c.name);
  return names;
}

int unknownCommand(const std::string& how, const std::string& name) {
  std::vector<std::string> names;
  for (const cli::Command& c : cli::commands()) names.push_back(c.name);
  std::cerr << "surrogate" << how << ": unknown command \"" << escapedText(name) << "\"; ";
  if (const auto near = nearestName(name, names)) std::cerr << "did you mean " << *near << "? ";
  std::cerr << "the commands are " << commandNames() << " (surrogate --help describes them)\n";
  return static_cast<int>(ErrorKind::Usage);
}

bool asksForHelp(int argc, char** argv) {
  for (int i = 2; i < argc; ++i)
    if (std::string(argv[i]) == "--help" || std::string(argv[i]) == "-h") return true;
  return false;
}

// surrogate help COMMAND: the command's own --help ("help help": the general help).
int helpFor(const std::string& name) {
  if (name == "help") {
    printUsage();
    return 0;
  }
  for (const cli::Command& c : cli::commands()) {
    if (name != c.name) continue;
    std::string command = c.name, help = "--help";
    char* args[] = {command.data(), help.data(), nullptr};
    return c.run(2, args);
  }
  return unknownCommand(" help", name);
}
}  // namespace

int main(int argc, char** argv) {
  reuseFreedMemory();  // before any thread starts: see core/resident.h
  // A file-size limit (ulimit -f) then fails the write with EFBIG, which the writer reports
  // and cleans up after, instead of killing the process with no word (core/atomic_file.h).
  std::signal(SIGXFSZ, SIG_IGN);
  if (argc >= 3 && std::string(argv[1]) == "help") return helpFor(argv[2]);
  if (argc < 2 || std::string(argv[1]) == "--help" || std::string(argv[1]) == "-h" ||
      std::string(argv[1]) == "help") {
    printUsage();
    return argc < 2 ? 2 : 0;
  }
  if (std::string(argv[1]) == "--version") {
    std::cout << cli::versionText();
    return 0;
  }
  const std::string name = argv[1];
  bool json = false;
  for (int i = 2; i < argc; ++i) json = json || std::string(argv[i]) == "--json";
  for (const cli::Command& c : cli::commands()) {
    if (name != c.name) continue;
    const int internal = static_cast<int>(ErrorKind::Internal);
    try {
      // An installation missing a data file stops every command before it reads or writes
      // anything, naming the file (core/resources.h); --help needs none.
      if (!asksForHelp(argc, argv)) requireDataFiles();
      return c.run(argc - 1, argv + 1);
    } catch (const Error& e) {
      return fail(json, name, e.exitCode(), e.file(), e.step(), e.message(), e.text());
    } catch (const std::bad_alloc&) {
      const std::string m = "out of memory; lower --memory or --threads";
      return fail(json, name, internal, "", "", m, m);
    } catch (const std::exception& e) {
      const std::string m = std::string("internal error: ") + e.what() +
                            " (please report this with the command you ran)";
      return fail(json, name, internal, "", "", m, m);
    }
  }
  return unknownCommand("", name);
}
