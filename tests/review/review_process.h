// Test support: `surrogate review --no-browser --port 0` on a capture, as a separate process,
// with the port it printed; stopped (SIGTERM) when the object goes.
#pragma once

#include <fcntl.h>
#include <signal.h>
#include <spawn.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <filesystem>
#include <fstream>
#include <regex>
#include <sstream>
#include <stdexcept>
#include <string>
#include <thread>
#include <vector>

extern char** environ;

namespace review_test {

class ReviewProcess {
 public:
  ReviewProcess(const std::filesystem::path& capture, const std::vector<std::string>& extra,
                const std::filesystem::path& logFile)
      : log_(logFile) {
    std::vector<std::string> words = {SURROGATE_EXE, "review", capture.string(), "--no-browser", "--port", "0"};
    words.insert(words.end(), extra.begin(), extra.end());
    std::vector<char*> argv;
    for (std::string& w : words) argv.push_back(w.data());
    argv.push_back(nullptr);
    posix_spawn_file_actions_t files;
    posix_spawn_file_actions_init(&files);
    posix_spawn_file_actions_addopen(&files, 1, log_.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
    posix_spawn_file_actions_adddup2(&files, 1, 2);
    const int failed = posix_spawn(&pid_, argv[0], &files, nullptr, argv.data(), environ);
    posix_spawn_file_actions_destroy(&files);
    if (failed) throw std::runtime_error("surrogate review could not be started");
    // The address it prints first ("Review of CAPTURE: http://127.0.0.1:PORT/").
    const std::regex address(R"(http://127\.0\.0\.1:(\d+)/)");
    for (int tries = 0; tries < 300; ++tries) {
      std::smatch m;
      const std::string text = output();
      if (std::regex_search(text, m, address)) {
        port_ = std::stoi(m[1].str());
        return;
      }
      int status = 0;
      if (waitpid(pid_, &status, WNOHANG) == pid_) {
        pid_ = -1;
        throw std::runtime_error("surrogate review ended at once: " + text);
      }
      std::this_thread::sleep_for(std::chrono::milliseconds(50));
    }
    throw std::runtime_error("surrogate review printed no address: " + output());
  }
  ~ReviewProcess() { stop(); }

  int port() const { return port_; }
  std::string output() const {
    std::ifstream in(log_);
    std::ostringstream s;
    s << in.rdbuf();
    return s.str();
  }
  // SIGTERM, then its exit status (-1 when it did not exit by itself within 10 s).
  int stop() {
    if (pid_ <= 0) return exit_;
    ::kill(pid_, SIGTERM);
    for (int tries = 0; tries < 200; ++tries) {
      int status = 0;
      if (waitpid(pid_, &status, WNOHANG) == pid_) {
        pid_ = -1;
        exit_ = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
        return exit_;
      }
      std::this_thread::sleep_for(std::chrono::milliseconds(50));
    }
    ::kill(pid_, SIGKILL);
    waitpid(pid_, nullptr, 0);
    pid_ = -1;
    return exit_ = -1;
  }

 private:
  std::filesystem::path log_;
  pid_t pid_ = -1;
  int port_ = 0;
  int exit_ = -1;
};

}  // namespace review_test
