#include "cli/progress.h"

#include <sys/ioctl.h>
#include <unistd.h>

#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <cstring>

namespace surrogate::cli {

namespace {

// The bar's width in characters: 30 when the terminal has room, down to 10 before the label
// is shortened (a long label says more than a long bar).
constexpr int kMaxBar = 30, kMinBar = 10;
// " [" + "] " + "100%", around the bar.
constexpr int kBarFrame = 8;
// The label's column when the terminal has room: the longest label of a re-execution
// ("re-executing: Hashing and reading metadata") fits. Every line of one terminal uses the
// same widths, so that successive bars line up.
constexpr int kLabelColumns = 44;
// Redraw at most this often within one label: drawing costs a system call.
constexpr auto kRedrawInterval = std::chrono::milliseconds(100);

int displayWidth(const std::string& s) {
  int n = 0;
  for (unsigned char c : s) n += (c & 0xC0) != 0x80;  // count UTF-8 lead bytes
  return n;
}

// The terminal's width on stderr, else $COLUMNS, else 80.
int terminalColumns() {
  winsize ws{};
  if (::ioctl(STDERR_FILENO, TIOCGWINSZ, &ws) == 0 && ws.ws_col > 0) return ws.ws_col;
  if (const char* env = std::getenv("COLUMNS")) {
    const int n = std::atoi(env);
    if (n > 0) return n;
  }
  return 80;
}

}  // namespace

ProgressMode progressMode(bool quiet) {
  if (quiet) return ProgressMode::Off;
  const char* env = std::getenv("SURROGATE_PROGRESS");
  if (env && std::strcmp(env, "lines") == 0) return ProgressMode::Lines;
  return ::isatty(STDERR_FILENO) ? ProgressMode::Bar : ProgressMode::Off;
}

std::string fitLabel(const std::string& label, int columns) {
  if (displayWidth(label) <= columns) return label;
  static const std::string kEllipsis = "\u2026";
  std::size_t cut = 0;  // end of the longest run of whole words that fits beside the ellipsis
  for (std::size_t space = label.find(' '); space != std::string::npos; space = label.find(' ', space + 1)) {
    if (displayWidth(label.substr(0, space)) + 1 > columns) break;
    cut = space;
  }
  std::string shown = label.substr(0, cut);
  while (!shown.empty() && std::strchr(" ,;:", shown.back())) shown.pop_back();
  return shown + kEllipsis;
}

ProgressBar::ProgressBar(bool quiet) : mode_(progressMode(quiet)) {}

ProgressBar::~ProgressBar() { finish(); }

void ProgressBar::update(const std::string& label, double fraction) {
  if (mode_ == ProgressMode::Off) return;
  std::lock_guard<std::mutex> lock(mutex_);
  const int percent = static_cast<int>(std::clamp(fraction, 0.0, 1.0) * 100);
  const auto now = std::chrono::steady_clock::now();
  if (label == label_ && percent <= lastPercent_) return;
  if (label == label_ && percent < 100 && now - lastDraw_ < kRedrawInterval) return;
  if (label != label_ && drawn_ && mode_ == ProgressMode::Bar) std::fputc('\n', stderr);
  label_ = label;
  lastPercent_ = percent;
  lastDraw_ = now;
  draw(label, percent);
  drawn_ = true;
}

void ProgressBar::draw(const std::string& label, int percent) {
  if (mode_ == ProgressMode::Lines) {
    std::fprintf(stderr, "progress\t%d\t%s\n", percent, label.c_str());
    std::fflush(stderr);
    return;
  }
  // One column is left free: writing the last column makes some terminals wrap the line.
  const int columns = terminalColumns() - 1;
  const int room = std::max(std::min(kLabelColumns, columns - kBarFrame - kMinBar), 1);
  const int barWidth = std::clamp(columns - kBarFrame - room, kMinBar, kMaxBar);
  const std::string shown = fitLabel(label, room);
  const int pad = std::max(room - displayWidth(shown), 0);
  const int filled = percent * barWidth / 100;
  std::fprintf(stderr, "\r%s%s [%s%s] %3d%%", shown.c_str(), std::string(pad, ' ').c_str(),
               std::string(filled, '#').c_str(), std::string(barWidth - filled, ' ').c_str(), percent);
  std::fflush(stderr);
}

void ProgressBar::finish() {
  if (mode_ == ProgressMode::Off) return;
  std::lock_guard<std::mutex> lock(mutex_);
  if (drawn_ && mode_ == ProgressMode::Bar) std::fputc('\n', stderr);
  drawn_ = false;
  label_.clear();
  lastPercent_ = -1;
}

}  // namespace surrogate::cli
