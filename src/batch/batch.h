// A batch: each item of a list (batch/work_list.h) taken through the steps asked for (run,
// pack, verify), one job per item, up to `jobs` at a time, each step a child process
// (batch/jobs.h), each attempt one line of the ledger (batch/ledger.h), and what is done and
// still valid skipped (batch/resume.h).
//
//   BatchOptions o;  o.steps = {"run", "pack", "verify"};  o.ledger = "ledger.jsonl";
//   const BatchResult r = runBatch(readWorkList("captures.txt"), o);
#pragma once

#include <cstdint>
#include <filesystem>
#include <functional>
#include <string>
#include <vector>

#include "batch/work_list.h"

namespace surrogate::batch {

// The steps in the order they run.
inline const std::vector<std::string> kSteps = {"run", "pack", "verify"};

// What happened to one step of a finished job.
struct StepOutcome {
  std::string step;
  std::string outcome;  // "done", "skipped" (done before and still valid), "failed", "not run"
  int exit = 0;
  int attempts = 0;     // attempts made by this batch
  double seconds = 0;
  std::uint64_t peakMemory = 0;
  std::string message;
};

struct JobReport {
  WorkItem item;
  std::vector<StepOutcome> steps;
  bool succeeded = true;
  bool workDone = false;  // some step ran (not all skipped)
  int exit = 0;           // the failed step's exit code
};

// --dry-run: what a batch would do with one item, step by step.
struct PlannedStep {
  std::string step;     // "run", "pack" or "verify"
  bool skipped = false; // done before and still valid
  std::string package;  // the package a pack writes or a verify checks; "" for run
  std::string why;      // why it runs: the ledger's or the capture's state, or "after STEP"
};

struct ItemPlan {
  WorkItem item;
  std::vector<PlannedStep> steps;
};

struct BatchOptions {
  std::vector<std::string> steps = kSteps;  // a subset of kSteps, in its order
  std::filesystem::path ledger;
  std::filesystem::path packagesDir;        // "" : beside each capture
  std::string packageFormat = "zip";        // "zip" or "tar": each package's file (--package-format)
  int jobs = 1;
  int threadsPerJob = 0;                    // 0: the cores shared among the jobs
  int retries = 1;                          // more attempts of a failed step in this batch
  std::uint64_t memory = 0;                 // bytes per job, 0: no budget
  bool reexecute = false;                   // verify --reexecute
  bool noReport = false;                    // run --no-report
  bool dryRun = false;
  std::string program;                      // the surrogate program; "" : this one
  // Each finished job, in the order they finish; and (finished, total) after each.
  std::function<void(const JobReport&)> jobFinished;
  std::function<void(std::size_t, std::size_t)> progress;
  // A job that waits for its capture, busy with another command (`why`), once per job.
  std::function<void(const WorkItem&, const std::string& why)> waiting;
  // --dry-run (or --verbose, before the work): each item's plan, in the list's order; unset,
  // no plan is made for a batch that runs.
  std::function<void(const ItemPlan&)> plan;
};

struct BatchResult {
  std::size_t items = 0, succeeded = 0, failed = 0, untouched = 0;  // untouched: all skipped
  int exitCode = 0;  // 0 when every job succeeded; else the highest exit code of a failed step (5 for a signal)
};

// Throws Error(Usage) for a step name it does not know, Error(Internal) when the ledger
// cannot be written; a job's failure is in its report and the ledger, never thrown.
BatchResult runBatch(const std::vector<WorkItem>& items, const BatchOptions& options);

// The exit code of a package's verification in words ("fixity failure", ...).
std::string verifyVerdict(int exit);

}  // namespace surrogate::batch
