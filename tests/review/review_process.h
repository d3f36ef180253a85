// Test support: `surrogate review --no-browser --port 0` on a capture, as a separate process,
// with the port and key it printed; stopped (SIGTERM) when the object goes.
#pragma once

#include <signal.h>
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

#include <httplib.h>

#include "e2e_support.h"

namespace review_test {

class ReviewProcess {
 public:
  ReviewProcess(const std::filesystem::path& capture, const std::vector<std::string>& extra,
                const std::filesystem::path& logFile)
      : log_(logFile) {
    std::vector<std::string> words = {"review", capture.string(), "--no-browser", "--port", "0"};
    words.insert(words.end(), extra.begin(), extra.end());
    pid_ = e2e::startSurrogate(words, log_);
    // The address it prints first ("Review of CAPTURE: http://127.0.0.1:PORT/?key=KEY").
    const std::regex address(R"(http://127\.0\.0\.1:(\d+)/\?key=([0-9a-f]{64})\n)");
    for (int tries = 0; tries < 300; ++tries) {
      std::smatch m;
      const std::string text = output();
      if (std::regex_search(text, m, address)) {
        port_ = std::stoi(m[1].str());
        key_ = m[2].str();
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
  const std::string& key() const { return key_; }
  // The Cookie header the page's requests carry once the browser has loaded the address.
  std::string cookie() const { return "surrogate-review-" + std::to_string(port_) + "=" + key_; }
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
  std::string key_;
  int exit_ = -1;
};

// A client with the page's cookie, as the browser has it once it loaded the printed address.
inline httplib::Client pageClient(const ReviewProcess& review) {
  httplib::Client client("127.0.0.1", review.port());
  client.set_default_headers({{"Cookie", review.cookie()}});
  return client;
}

}  // namespace review_test
