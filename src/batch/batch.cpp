// A batch's schedule: up to `jobs` jobs at a time, each started on its next step, its child
// polled, parked while its capture is busy and taken up again, and counted when finished. The
// parts of a job's way live by concern (batch/runner.h names them).
#include "batch/batch.h"

#include <algorithm>
#include <chrono>
#include <deque>
#include <memory>
#include <thread>
#include <utility>

#include "batch/runner.h"
#include "core/error.h"
#include "core/identity.h"

namespace surrogate::batch {

Runner::Runner(const std::vector<WorkItem>& items, const BatchOptions& options) : items_(items), o_(options) {
  for (const std::string& s : o_.steps)
    if (std::find(kSteps.begin(), kSteps.end(), s) == kSteps.end())
      throw Error(ErrorKind::Usage, "--do " + s, "command line", "is not a step: give run, pack and/or verify");
  program_ = o_.program.empty() ? selfExecutable() : o_.program;
  const int cores = static_cast<int>(std::max(1u, std::thread::hardware_concurrency()));
  threads_ = o_.threadsPerJob > 0 ? o_.threadsPerJob : std::max(1, cores / std::max(1, o_.jobs));
  host_ = hostName();
  requireDistinctPackages(items_, o_.packagesDir, o_.packageFormat);
  if (!o_.dryRun) requireWritableLedger(o_.ledger);
  ledgerOffset_ = readLedgerSince(o_.ledger, 0, ledger_);
  for (std::size_t i = 0; i < ledger_.entries.size(); ++i) byItem_[ledger_.entries[i].capture].push_back(i);
}

BatchResult Runner::run() {
  BatchResult result;
  result.items = items_.size();
  if (o_.dryRun) {
    for (const WorkItem& item : items_) o_.plan(planOf(item));
    return result;
  }
  // --verbose: the same plan, said before the work starts.
  if (o_.plan)
    for (const WorkItem& item : items_) o_.plan(planOf(item));
  std::deque<std::size_t> queue;
  for (std::size_t i = 0; i < items_.size(); ++i) queue.push_back(i);
  std::vector<std::unique_ptr<Job>> active;
  // Jobs waiting for their capture's lock, with when each may try again, in that order.
  std::deque<std::pair<std::unique_ptr<Job>, std::chrono::steady_clock::time_point>> parked;
  std::size_t finished = 0;
  while (!queue.empty() || !active.empty() || !parked.empty()) {
    bool changed = false;
    while (static_cast<int>(active.size()) < std::max(1, o_.jobs)) {
      std::unique_ptr<Job> job;
      if (!parked.empty() && parked.front().second <= std::chrono::steady_clock::now()) {
        job = std::move(parked.front().first);
        parked.pop_front();
        job->waiting = false;
      } else if (!queue.empty()) {
        job = std::make_unique<Job>();
        job->item = items_[queue.front()];
        queue.pop_front();
        job->package = packageOf(job->item);
        job->report.item = job->item;
      } else {
        break;
      }
      if (!job->item.isPackage &&
          job->claim.claim(job->item.where()) == CaptureClaim::Outcome::HeldByAnother &&
          waitForCapture(*job, "another batch is working on this capture")) {
        parked.emplace_back(std::move(job), std::chrono::steady_clock::now() + kBusyRetryInterval);
        changed = true;
        continue;
      }
      refreshLedger();  // what the batches beside this one have done meanwhile
      advance(*job);
      active.push_back(std::move(job));
      changed = true;
    }
    for (auto& job : active)
      if (job->child && job->child->poll()) {
        ended(*job);
        if (!job->waiting) advance(*job);
        changed = true;
      }
    for (auto it = active.begin(); it != active.end();) {
      if ((*it)->waiting) {
        (*it)->claim.release();
        parked.emplace_back(std::move(*it), std::chrono::steady_clock::now() + kBusyRetryInterval);
        it = active.erase(it);
      } else {
        ++it;
      }
    }
    for (auto it = active.begin(); it != active.end();) {
      if (!(*it)->finished) {
        ++it;
        continue;
      }
      const JobReport& r = (*it)->report;
      countFinished(result, r);
      ++finished;
      if (o_.jobFinished) o_.jobFinished(r);
      if (o_.progress) o_.progress(finished, items_.size());
      it = active.erase(it);
    }
    if (!changed) std::this_thread::sleep_for(kPollInterval);
  }
  return result;
}

BatchResult runBatch(const std::vector<WorkItem>& items, const BatchOptions& options) {
  Runner runner(items, options);
  return runner.run();
}

}  // namespace surrogate::batch
