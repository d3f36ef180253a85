// The `surrogate` subcommands. Each parses its options and calls the libraries: nothing of
// substance lives here (a thin CLI over the libraries: docs/developer-guide.md, "Code
// conventions").
#pragma once

#include <optional>
#include <string>
#include <vector>

#include "carrier/carrier.h"
#include "carrier/summary.h"
#include "cli/args.h"

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
int runCommandPublish(int argc, char** argv);
int runCommandReport(int argc, char** argv);
int runCommandVerify(int argc, char** argv);
int runCommandAudit(int argc, char** argv);
int runCommandBatch(int argc, char** argv);

// Shared by commands: the head of a command's --help.
std::string usageHeader(const std::string& synopsis, const std::string& description);
// When --help was given: prints the command's help (usageHeader and its options) and returns
// true, so the command returns 0.
bool helpShown(const Args& args, const std::vector<OptionSpec>& specs, const std::string& synopsis,
               const std::string& description);
// Prints, one a line under "  warning: ", the warnings the light stages (spheres, highlights,
// lights and their checks) and the fits logged in `c`: a highlight refused on one sphere of
// two, a doubtful one, an accepted check, a fit damped for its narrow cone of lights. The user
// reads them here, not only in the carrier. At most `most`, then how many more.
void printStageWarnings(const carrier::Carrier& c, std::size_t most = 8);

// Prints the carrier's warnings (carrier::CarrierSummary::warnings) grouped by the step that
// logged them, a heading line per step ("    s3 SphereDetection:") over its warnings' one-line
// texts, in at most `mostLines` lines in all (0: no limit); the warnings left out are counted
// in one more line, "and N more: " + `more`. Prints nothing when there are none.
void printWarnings(const carrier::CarrierSummary& s, std::size_t mostLines, const std::string& more);

// The file a command writes: -o (also --o) or --output.
std::optional<std::string> outputOption(const Args& args);

}  // namespace surrogate::cli
