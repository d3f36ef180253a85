// surrogate: the command-line tool. Dispatches to a subcommand and turns errors into a
// message naming the file and an exit code:
//   0 success (verify: the package is sound)
//   1 bad input: a capture, image or file that cannot be processed
//   2 bad usage (options), or an invalid package
//   3 fixity failure (verify)
//   4 not reproduced (verify --reexecute)
//   5 internal error (a bug, or the environment: disk full, missing data files)
#include <exception>
#include <iostream>
#include <string>

#include "cli/commands.h"
#include "core/error.h"
#include "core/version.h"

using namespace surrogate;

namespace {
void printUsage() {
  std::cout << "surrogate " << surrogateVersion()
            << ": digital surrogates of Highlight-RTI captures, with their provenance\n\n"
               "usage: surrogate COMMAND [options]    (surrogate COMMAND --help for details)\n\n"
               "commands:\n";
  for (const cli::Command& c : cli::commands()) {
    std::string name = c.name;
    name.resize(10, ' ');
    std::cout << "  " << name << c.summary << "\n";
  }
  std::cout << "\nexit codes: 0 success, 1 bad input, 2 bad usage or invalid package, "
               "3 fixity failure, 4 not reproduced, 5 internal error\n";
}
}  // namespace

int main(int argc, char** argv) {
  if (argc < 2 || std::string(argv[1]) == "--help" || std::string(argv[1]) == "-h" ||
      std::string(argv[1]) == "help") {
    printUsage();
    return argc < 2 ? 2 : 0;
  }
  if (std::string(argv[1]) == "--version") {
    std::cout << "surrogate " << surrogateVersion() << "\n";
    return 0;
  }
  const std::string name = argv[1];
  for (const cli::Command& c : cli::commands()) {
    if (name != c.name) continue;
    try {
      return c.run(argc - 1, argv + 1);
    } catch (const Error& e) {
      std::cerr << "surrogate " << name << ": " << e.what() << "\n";
      return e.exitCode();
    } catch (const std::bad_alloc&) {
      std::cerr << "surrogate " << name << ": out of memory; lower --memory or --threads\n";
      return static_cast<int>(ErrorKind::Internal);
    } catch (const std::exception& e) {
      std::cerr << "surrogate " << name << ": internal error: " << e.what()
                << " (please report this with the command you ran)\n";
      return static_cast<int>(ErrorKind::Internal);
    }
  }
  std::cerr << "surrogate: unknown command \"" << name << "\" (run surrogate --help)\n";
  return static_cast<int>(ErrorKind::Usage);
}
