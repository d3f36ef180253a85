// Waiting and locks: a batch's claim on a capture folder, and how long a job waits for a
// capture that another Surrogate command holds (the job's side of it is Runner::waitForCapture
// and Runner::processedMeanwhile, batch/waiting.cpp).
//
//   CaptureClaim claim;
//   if (claim.claim(folder) == CaptureClaim::Outcome::HeldByAnother) ... wait kBusyRetryInterval
#pragma once

#include <chrono>
#include <filesystem>

namespace surrogate::batch {

// A job whose capture another Surrogate command holds looks again after this long, and gives
// up (the refusal recorded as the step's failure) after kBusyWaitLimit: a lock is held by a
// live process only (flock), so the wait is for work being done, a 24 Mpx capture's run, pack
// and verify in about a minute.
inline constexpr std::chrono::seconds kBusyRetryInterval{1};
inline constexpr std::chrono::minutes kBusyWaitLimit{30};

// A batch's claim on a capture folder, held from its job's first step to its last step's
// ledger line: a second batch on the same list (a rerun while the first still runs, another
// Slurm task) finds the capture claimed and comes back later, rather than taking the capture's
// lock in the moment between a step's end and its ledger line and doing the step again. An
// exclusive flock() of CAPTURE/.surrogate/batch-claim, apart from the lock each step's command
// takes itself; it goes with the process.
class CaptureClaim {
 public:
  enum class Outcome { Claimed, HeldByAnother, NotAClaimableFolder };

  Outcome claim(const std::filesystem::path& capture);
  void release();

  CaptureClaim() = default;
  CaptureClaim(const CaptureClaim&) = delete;
  CaptureClaim& operator=(const CaptureClaim&) = delete;
  ~CaptureClaim() { release(); }

 private:
  int fd_ = -1;
};

}  // namespace surrogate::batch
