// Inside a batch (batch/batch.h's runBatch): a job, one item on its way through the steps, and
// the runner that holds the batch's view of the ledger and takes each job through. Its parts
// live by concern: batch.cpp the schedule (jobs started, polled, parked and finished),
// planning.cpp what is done and still valid (and the ledger as this batch knows it),
// job_steps.cpp each step's child and its ledger line, waiting.cpp the capture's claim and the
// waits for a busy capture, outcomes.cpp the job's report and the batch's result.
#pragma once

#include <chrono>
#include <cstdint>
#include <filesystem>
#include <functional>
#include <memory>
#include <optional>
#include <set>
#include <string>
#include <unordered_map>
#include <vector>

#include "batch/batch.h"
#include "batch/jobs.h"
#include "batch/ledger.h"
#include "batch/waiting.h"
#include "batch/work_list.h"

namespace surrogate::batch {

struct Job {
  WorkItem item;
  CaptureClaim claim;          // a capture item's, while the job is active
  std::filesystem::path package;
  std::size_t next = 0;        // index into the steps
  int attempts = 0;            // of the current step, in this batch
  // Another Surrogate command held the capture's lock when the step started (another batch on
  // the same list, a requeued Slurm task, a review's Apply): the job waits in the batch's
  // queue, and its step is checked again when it comes back (the other may have done it).
  bool waiting = false;
  bool recheck = false;
  std::optional<std::chrono::steady_clock::time_point> busySince;
  std::string busySinceUtc;    // the same, as the carrier writes times
  bool forcePack = false;
  std::unique_ptr<Child> child;
  LedgerEntry entry;           // the attempt running
  JobReport report;
  bool finished = false;
};

// A finished job counted into the batch's result (outcomes.cpp).
void countFinished(BatchResult& result, const JobReport& report);

class Runner {
 public:
  // Throws Error(Usage) for a step it does not know; reads the ledger (batch.cpp).
  Runner(const std::vector<WorkItem>& items, const BatchOptions& options);
  BatchResult run();

 private:
  // Planning (planning.cpp).
  // The steps of `o_.steps` that apply to the item (a package has only verify).
  bool applies(const Job& job, const std::string& step) const { return !job.item.isPackage || step == "verify"; }
  std::filesystem::path packageOf(const WorkItem& item) const;
  // The item's lines, in file order (a copy: a ledger of 100 000 packages is not searched whole
  // for each decision).
  Ledger ledgerOf(const std::string& item) const;
  const LedgerEntry* lastMatching(const std::string& item, const std::function<bool(const LedgerEntry&)>& wanted) const;
  const LedgerEntry* lastSuccess(const std::string& item, const std::string& step) const;
  // The ledger's record of the package file as it was last seen (by a pack or a verify), so
  // that an unchanged package is not read again.
  const LedgerEntry* knownPackage(const std::string& item) const;
  // Whether the step is done and still valid; `why` says why not.
  bool stillValid(const Job& job, const std::string& step, std::string& why) const;
  ItemPlan planOf(const WorkItem& item) const;
  // The attempt appended to the ledger and to this batch's view of it.
  void record(LedgerEntry e);
  // An entry as this batch knows its own: the item, step and start time (milliseconds) on this
  // host.
  static std::string ownKey(const LedgerEntry& e);
  // The lines appended to the ledger since this batch last read it, its own aside (record()
  // has them already).
  void refreshLedger();

  // Running jobs (job_steps.cpp).
  std::vector<std::string> commandFor(const Job& job, const std::string& step) const;
  LedgerEntry newEntry(const Job& job, const std::string& step) const;
  // A step that ends without a child: the pack of a package that exists already.
  // Returns true when it was settled here (adopted or refused).
  bool settlePackHere(Job& job);
  // Starts the job's next step that is not done, or finishes the job.
  void advance(Job& job);
  // The step's child has ended: its line in the ledger, then a retry or the next step.
  void ended(Job& job);

  // Waiting and locks (waiting.cpp).
  // The capture is busy (claimed by another batch, or locked by another command): whether the
  // job may wait for it, kBusyRetryInterval between looks, up to kBusyWaitLimit from the first
  // time; after that the refusal is recorded as the step's failure. Its step is checked again
  // when it comes back: the other may have done it.
  bool waitForCapture(Job& job, const std::string& why) const;
  // Whether the capture's carrier records a completed run that ended after the job found the
  // capture busy: the command it waited for processed it (another batch's run, whose ledger
  // line may still be on its way, or a review's Apply), and running it again would only add
  // a run to its history. A pack it waited for is recognised by its package (settlePackHere).
  bool processedMeanwhile(const Job& job) const;

  // Outcomes (outcomes.cpp): the step's outcome in the job's report, and the job moved on
  // to its next step (or past the rest, "not run", when it failed).
  void finishStep(Job& job, const std::string& step, const std::string& outcome, const LedgerEntry* e,
                  const std::string& message);

  const std::vector<WorkItem>& items_;
  const BatchOptions& o_;
  std::string program_, host_;
  int threads_ = 1;
  Ledger ledger_;
  std::uint64_t ledgerOffset_ = 0;           // where the last read of the ledger ended
  std::multiset<std::string> ownUnread_;     // lines this batch wrote that it has not read back
  std::unordered_map<std::string, std::vector<std::size_t>> byItem_;  // positions in ledger_.entries
};

}  // namespace surrogate::batch
