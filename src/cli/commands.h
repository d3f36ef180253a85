// The `surrogate` subcommands. Each parses its options and calls the libraries: nothing of
// substance lives here (see STYLE.md: a thin CLI over the libraries).
#pragma once

#include <string>
#include <vector>

namespace surrogate::cli {

struct Command {
  const char* name;
  const char* summary;
  int (*run)(int argc, char** argv);  // argv[0] is the command name
};

const std::vector<Command>& commands();

int runCommandRun(int argc, char** argv);
int runCommandPack(int argc, char** argv);
int runCommandInfo(int argc, char** argv);
int runCommandLights(int argc, char** argv);
int runCommandFit(int argc, char** argv);
int runCommandRender(int argc, char** argv);
int runCommandReport(int argc, char** argv);
int runCommandVerify(int argc, char** argv);

// Shared by commands: prints `help` and returns 0 if --help was given.
std::string usageHeader(const std::string& synopsis, const std::string& description);

}  // namespace surrogate::cli
