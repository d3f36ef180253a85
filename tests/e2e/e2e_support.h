// Support for end-to-end tests: running the programs, making generated captures, and
// snapshotting a folder's files to prove nothing was modified.
#pragma once

#include <filesystem>
#include <map>
#include <string>
#include <vector>

namespace e2e {

struct CommandResult {
  int exitCode = -1;
  std::string output;  // stdout and stderr together
};

// Runs a shell command line, capturing its output.
CommandResult runShell(const std::string& commandLine);
// Runs `surrogate ARGS`.
CommandResult surrogate(const std::string& args);
// Starts `surrogate ARGS...` without waiting (no shell), its standard output and error both to
// the file `output` (made or emptied; /dev/null for none); its process id, for the test to
// signal and wait for. Throws std::runtime_error when it cannot be started.
int startSurrogate(const std::vector<std::string>& args, const std::filesystem::path& output);

// A fresh, empty temporary folder for one test (removed at process exit is not needed: the
// system's /tmp is fine; each call gets a new name).
std::filesystem::path freshDir(const std::string& name);

// A small generated capture (DNG originals + JPEG exports), made once per test process and
// copied to `dir` for each test that wants to change it.
std::filesystem::path smallCapture(const std::filesystem::path& dir, int images = 8);

// A capture made by `surrogate-generate --out DIR ARGUMENTS` in a fresh folder named `name`
// (DIR is its capture/), its truth/ moved beside it: outside the capture, where no tool reads
// it. Throws std::runtime_error with the generator's output when the generator fails.
std::filesystem::path generatedWithTruth(const std::string& name, const std::string& arguments);

// smallCapture after `surrogate run --no-report` (a carrier, .lp, .ptm and .rti), made once per
// test process and copied to `dir`/cap for each test.
std::filesystem::path processedCapture(const std::filesystem::path& dir);

// SHA-256 of every regular file under `root`, by relative path.
std::map<std::string, std::string> snapshot(const std::filesystem::path& root);

std::string quote(const std::filesystem::path& p);

// The whole content of a file (empty if it cannot be read).
std::string bytesOf(const std::filesystem::path& p);

}  // namespace e2e
