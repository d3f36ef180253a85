// Waiting and locks: the batch's claim on a capture folder (an flock() of its own), and a job
// that waits for a capture another Surrogate command holds, then finds whether that command
// did its step meanwhile.
#include "batch/waiting.h"

#include <fcntl.h>
#include <sys/file.h>
#include <unistd.h>

#include <chrono>
#include <string>
#include <system_error>

#include "batch/runner.h"
#include "capture/capture.h"
#include "carrier/carrier.h"
#include "core/error.h"

namespace surrogate::batch {

namespace fs = std::filesystem;

CaptureClaim::Outcome CaptureClaim::claim(const fs::path& capture) {
  if (!capture::hasSourceFolder(capture)) return Outcome::NotAClaimableFolder;  // the run step says what is wrong
  std::error_code ec;
  fs::create_directories(capture / capture::kWorkDir, ec);
  const fs::path file = capture / capture::kWorkDir / "batch-claim";
  fd_ = ::open(file.c_str(), O_RDWR | O_CREAT | O_CLOEXEC | O_NOFOLLOW, 0644);
  if (fd_ < 0) return Outcome::NotAClaimableFolder;  // read-only: no step can write there either
  if (::flock(fd_, LOCK_EX | LOCK_NB) == 0) return Outcome::Claimed;
  release();
  return Outcome::HeldByAnother;
}

void CaptureClaim::release() {
  if (fd_ >= 0) ::close(fd_);
  fd_ = -1;
}

bool Runner::waitForCapture(Job& job, const std::string& why) const {
  const auto now = std::chrono::steady_clock::now();
  if (!job.busySince) {
    job.busySince = now;
    job.busySinceUtc = carrier::timestampNow();
    if (o_.waiting) o_.waiting(job.item, why);
  }
  job.recheck = true;
  return now - *job.busySince < kBusyWaitLimit;
}

bool Runner::processedMeanwhile(const Job& job) const {
  try {
    const carrier::Carrier c = carrier::loadCarrier(fs::path(job.item.where()) / capture::kCarrierPath);
    for (auto r = c.header.runs.rbegin(); r != c.header.runs.rend(); ++r)
      if (r->command == "run") return r->outcome == "completed" && r->ended >= job.busySinceUtc;
  } catch (const Error&) {
    // No carrier, or one this version cannot read: the run step runs and says what is wrong.
  }
  return false;
}

}  // namespace surrogate::batch
