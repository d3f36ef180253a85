// A progress bar on the terminal (stderr), silent when stderr is not a terminal or with
// --quiet, so logs and pipes stay clean.
#pragma once

#include <chrono>
#include <mutex>
#include <string>

namespace surrogate::cli {

class ProgressBar {
 public:
  explicit ProgressBar(bool quiet);
  ~ProgressBar();
  // Thread-safe; redraws at most ten times a second, and always at 100 %.
  void update(const std::string& label, double fraction);
  void finish();

 private:
  bool enabled_;
  std::mutex mutex_;
  std::string label_;
  int lastPercent_ = -1;
  std::chrono::steady_clock::time_point lastDraw_{};
  bool drawn_ = false;
};

}  // namespace surrogate::cli
