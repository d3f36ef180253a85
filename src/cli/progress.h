// Progress of long work, on standard error.
//
// On a terminal: a bar redrawn in place, one line per step, its label shortened at a word
// boundary (with an ellipsis) to leave the bar room in the terminal's width. When standard
// error is not a terminal (logs, pipes, CI): nothing, so logs stay clean. With the environment
// variable SURROGATE_PROGRESS=lines, on a terminal or not: one line per update a program can
// read, "progress<TAB>PERCENT<TAB>LABEL" (the whole label). --quiet silences both.
#pragma once

#include <chrono>
#include <functional>
#include <mutex>
#include <string>

namespace surrogate::cli {

// How progress is shown: the environment and stderr decide, --quiet overrides.
enum class ProgressMode { Off, Bar, Lines };
ProgressMode progressMode(bool quiet);

// The label fitted into `columns` display columns: whole when it fits, else cut after the
// last whole word that leaves room for "…" (never inside a word). Columns are counted as
// UTF-8 code points.
std::string fitLabel(const std::string& label, int columns);

class ProgressBar {
 public:
  explicit ProgressBar(bool quiet);
  ~ProgressBar();
  // Thread-safe. Within one label the percentage only grows (updates from worker threads may
  // arrive out of order); redraws at most ten times a second, and always at 100 %.
  void update(const std::string& label, double fraction);
  void finish();
  // A callback for the libraries' (label, fraction) progress that updates this bar.
  std::function<void(const std::string&, double)> callback() {
    return [this](const std::string& label, double f) { update(label, f); };
  }

 private:
  void draw(const std::string& label, int percent);

  ProgressMode mode_;
  std::mutex mutex_;
  std::string label_;
  int lastPercent_ = -1;
  std::chrono::steady_clock::time_point lastDraw_{};
  bool drawn_ = false;
};

}  // namespace surrogate::cli
