// Outcomes, what a batch sums up: a step's outcome in its job's report, the job's report
// counted into the batch's result (its exit code the worst of the failed steps'), and a
// verification's exit code in words.
#include <algorithm>
#include <string>

#include "batch/runner.h"

namespace surrogate::batch {

std::string verifyVerdict(int exit) {
  switch (exit) {
    case 0: return "sound";
    case 1: return "cannot be read";
    case 2: return "invalid package";
    case 3: return "fixity failure";
    case 4: return "not reproduced";
    default: return "error";
  }
}

void Runner::finishStep(Job& job, const std::string& step, const std::string& outcome, const LedgerEntry* e,
                        const std::string& message) {
  StepOutcome s;
  s.step = step;
  s.outcome = outcome;
  s.attempts = job.attempts;
  s.message = message;
  if (e) {
    s.exit = e->exit;
    s.seconds = e->seconds;
    s.peakMemory = e->peakMemory;
  }
  job.report.steps.push_back(s);
  if (outcome == "failed") {
    job.report.succeeded = false;
    job.report.exit = s.exit;
    for (std::size_t k = job.next + 1; k < o_.steps.size(); ++k)
      if (applies(job, o_.steps[k]))
        job.report.steps.push_back({o_.steps[k], "not run", 0, 0, 0, 0, "the " + step + " failed"});
    job.next = o_.steps.size();
  } else {
    ++job.next;
  }
  job.attempts = 0;
  job.forcePack = false;
}

void countFinished(BatchResult& result, const JobReport& r) {
  if (r.succeeded) ++result.succeeded;
  else {
    ++result.failed;
    result.exitCode = std::max(result.exitCode, r.exit > 5 ? 5 : std::max(r.exit, 1));
  }
  if (!r.workDone && r.succeeded) ++result.untouched;
}

}  // namespace surrogate::batch
