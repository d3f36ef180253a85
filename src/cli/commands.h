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
int runCommandReview(int argc, char** argv);
int runCommandVerify(int argc, char** argv);
int runCommandAudit(int argc, char** argv);
int runCommandBatch(int argc, char** argv);

// When --help was given: prints the command's help (Args::describe) and returns true, so the
// command returns 0.
bool helpShown(const Args& args, const std::vector<OptionSpec>& specs, const CommandHelp& help);
// The exit codes most commands share: 0 `success`, 1 bad input (a write the system refused
// among them: atomic_file.h reports it as Input), 2 bad usage, 5 internal error; `more` adds
// the command's own (3 for a changed original), in order of code.
std::vector<std::pair<int, std::string>> commonExitCodes(const std::string& success,
                                                         std::vector<std::pair<int, std::string>> more = {});
// The meanings every --help gives these codes the same words: a write the system refused is
// exit 1, with the file named (core/atomic_file.h), and so is a damaged installation (core/resources.h:
// "reinstall Surrogate"); exit 5 is a bug or memory, never the disk.
inline constexpr const char* kWriteRefused = "a write the system refused (disk full, read-only, no permission, a file-size limit)";
inline constexpr const char* kInternalError =
    "internal error: a bug, or out of memory (a data file missing from the installation is exit 1: reinstall Surrogate)";
inline constexpr const char* kChangedOriginal =
    "an original no longer matches the SHA-256 the carrier records (it is evidence: restore it, or accept the "
    "change with run --accept-changed PATH --reason WHY)";
// Prints the carrier's warnings (carrier::CarrierSummary::warnings) grouped by the step that
// logged them, a heading line per step ("    s3 SphereDetection:") over its warnings' one-line
// texts, in at most `mostLines` lines in all (0: no limit); the warnings left out are counted
// in one more line, "and N more: " + `more`. Prints nothing when there are none.
void printWarnings(const carrier::CarrierSummary& s, std::size_t mostLines, const std::string& more);
// The most lines of warnings `run` and `lights` print: a screenful with the lines above them.
inline constexpr std::size_t kWarningLines = 15;

// A file a command wrote, for printFileList: its label ("result", "assembly"), the folder it is
// in (the capture) and its path there.
struct ListedFile {
  std::string label;
  std::string root;
  std::string path;  // relative to root, with '/'
};
// Prints "  LABEL: ROOT/PATH" a line. Unless `verbosity` is Verbose, a folder two or more levels
// below the root (finished-files/web/, not finished-files/ itself) holding more than
// kFilesListedPerFolder files of one label, in it or below, is one line with their count: a
// tiled web copy writes hundreds of files.
inline constexpr std::size_t kFilesListedPerFolder = 8;
void printFileList(const std::vector<ListedFile>& files, Verbosity verbosity);

// The file a command writes: -o (also --o) or --output.
std::optional<std::string> outputOption(const Args& args);

}  // namespace surrogate::cli
