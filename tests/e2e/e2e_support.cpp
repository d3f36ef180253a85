#include "e2e_support.h"

#include <fcntl.h>
#include <spawn.h>
#include <sys/wait.h>
#include <unistd.h>

#include <array>
#include <cstring>
#include <cstdio>
#include <fstream>
#include <sstream>
#include <stdexcept>

#include "core/digest.h"

namespace fs = std::filesystem;

extern char** environ;

namespace e2e {

std::string quote(const fs::path& p) {
  std::string out = "'";
  for (char c : p.string()) {
    if (c == '\'') out += "'\\''";
    else out += c;
  }
  return out + "'";
}

CommandResult runShell(const std::string& commandLine) {
  CommandResult r;
  FILE* pipe = ::popen((commandLine + " 2>&1").c_str(), "r");
  if (!pipe) throw std::runtime_error("popen failed");
  std::array<char, 4096> buffer;
  while (std::size_t n = std::fread(buffer.data(), 1, buffer.size(), pipe)) r.output.append(buffer.data(), n);
  const int status = ::pclose(pipe);
  r.exitCode = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  return r;
}

CommandResult surrogate(const std::string& args) {
  return runShell(std::string(SURROGATE_EXE) + " " + args);
}

int startSurrogate(const std::vector<std::string>& args, const fs::path& output) {
  std::vector<std::string> words = {SURROGATE_EXE};
  words.insert(words.end(), args.begin(), args.end());
  std::vector<char*> argv;
  for (std::string& w : words) argv.push_back(w.data());
  argv.push_back(nullptr);
  posix_spawn_file_actions_t files;
  posix_spawn_file_actions_init(&files);
  posix_spawn_file_actions_addopen(&files, 1, output.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
  posix_spawn_file_actions_adddup2(&files, 1, 2);
  pid_t pid = -1;
  const int failed = posix_spawn(&pid, argv[0], &files, nullptr, argv.data(), environ);
  posix_spawn_file_actions_destroy(&files);
  if (failed) throw std::runtime_error(std::string("surrogate could not be started: ") + std::strerror(failed));
  return pid;
}

fs::path freshDir(const std::string& name) {
  static int counter = 0;
  const fs::path dir = fs::temp_directory_path() /
                       ("surrogate-e2e-" + std::to_string(::getpid()) + "-" + name + "-" +
                        std::to_string(counter++));
  fs::remove_all(dir);
  fs::create_directories(dir);
  return dir;
}

fs::path generatedWithTruth(const std::string& name, const std::string& arguments) {
  const fs::path capture = freshDir(name) / "capture";
  const CommandResult r = runShell(std::string(GENERATOR_EXE) + " --out " + quote(capture) + " " + arguments);
  if (r.exitCode != 0) throw std::runtime_error("generator failed: " + r.output);
  fs::rename(capture / "truth", capture.parent_path() / "truth");
  return capture;
}

fs::path smallCapture(const fs::path& dir, int images) {
  static std::map<int, fs::path> made;
  if (!made.count(images)) {
    const fs::path source = freshDir("generated-" + std::to_string(images)) / "capture";
    const CommandResult r = runShell(std::string(GENERATOR_EXE) + " --out " + quote(source) +
                                     " --images " + std::to_string(images) +
                                     " --width 400 --height 300 --sphere-radius 45 --seed 7");
    if (r.exitCode != 0) throw std::runtime_error("generator failed: " + r.output);
    made[images] = source;
  }
  const fs::path target = dir / "capture";
  fs::copy(made[images], target, fs::copy_options::recursive);
  fs::remove_all(target / "truth");  // the truth is for the tests, not part of a capture
  return target;
}

fs::path processedCapture(const fs::path& dir) {
  static const fs::path made = [] {
    const fs::path capture = smallCapture(freshDir("processed-source"), 8);
    const CommandResult r = surrogate("run " + quote(capture) + " --quiet --no-report");
    if (r.exitCode != 0) throw std::runtime_error("the run of the sample capture failed: " + r.output);
    return capture;
  }();
  fs::copy(made, dir / "cap", fs::copy_options::recursive);
  return dir / "cap";
}

std::map<std::string, std::string> snapshot(const fs::path& root) {
  std::map<std::string, std::string> out;
  for (const auto& entry : fs::recursive_directory_iterator(root)) {
    if (!entry.is_regular_file()) continue;
    out[fs::relative(entry.path(), root).generic_string()] =
        surrogate::digestFile(entry.path()).sha256;
  }
  return out;
}

std::string bytesOf(const std::filesystem::path& p) {
  std::ifstream f(p, std::ios::binary);
  std::ostringstream s;
  s << f.rdbuf();
  return s.str();
}

}  // namespace e2e
