#include "cli/progress.h"

#include <unistd.h>

#include <algorithm>
#include <cstdio>

namespace surrogate::cli {

ProgressBar::ProgressBar(bool quiet) : enabled_(!quiet && ::isatty(STDERR_FILENO)) {}

ProgressBar::~ProgressBar() { finish(); }

void ProgressBar::update(const std::string& label, double fraction) {
  if (!enabled_) return;
  std::lock_guard<std::mutex> lock(mutex_);
  const int percent = static_cast<int>(std::clamp(fraction, 0.0, 1.0) * 100);
  const auto now = std::chrono::steady_clock::now();
  if (label == label_ && percent == lastPercent_) return;
  if (label == label_ && percent < 100 && now - lastDraw_ < std::chrono::milliseconds(100)) return;
  if (label != label_ && drawn_) std::fputc('\n', stderr);
  label_ = label;
  lastPercent_ = percent;
  lastDraw_ = now;
  constexpr int kWidth = 30;
  const int filled = percent * kWidth / 100;
  std::fprintf(stderr, "\r%-32.32s [%s%s] %3d%%", label.c_str(), std::string(filled, '#').c_str(),
               std::string(kWidth - filled, ' ').c_str(), percent);
  std::fflush(stderr);
  drawn_ = true;
}

void ProgressBar::finish() {
  if (!enabled_) return;
  std::lock_guard<std::mutex> lock(mutex_);
  if (drawn_) std::fputc('\n', stderr);
  drawn_ = false;
  label_.clear();
  lastPercent_ = -1;
}

}  // namespace surrogate::cli
