// Running jobs: each step of a job as a child process (the command it runs, with its threads
// and memory), the pack settled without one when its package exists already, and the step's
// line in the ledger when the child ends, with a retry or the next step.
#include <algorithm>
#include <cstdint>
#include <filesystem>
#include <memory>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "archive/package.h"
#include "archive/package_reader.h"
#include "batch/resume.h"
#include "batch/runner.h"
#include "batch/step_output.h"
#include "capture/capture.h"
#include "capture/lock.h"
#include "core/error.h"
#include "core/memory_budget.h"
#include "core/version.h"

namespace surrogate::batch {

namespace fs = std::filesystem;

namespace {

// The least streaming budget `run --memory` takes.
constexpr std::uint64_t kLeastJobBudget = 64ull << 20;

}  // namespace

std::vector<std::string> Runner::commandFor(const Job& job, const std::string& step) const {
  std::vector<std::string> a;
  const std::string threads = std::to_string(threads_);
  // Paths as paths, never options: an item "--help" was taken as run --help, which did
  // nothing and exited 0, and a capture folder "-h" was never processed.
  const std::string item = pathArgument(job.item.where()), package = pathArgument(job.package.string());
  if (step == "run") {
    a = {"run", item, "--quiet", "--json", "--threads", threads};
    if (o_.noReport) a.push_back("--no-report");
  } else if (step == "pack") {
    a = {"pack", item, "-o", package, "--quiet", "--json", "--threads", threads};
    if (o_.noReport) a.push_back("--no-report");
    if (job.forcePack) a.push_back("--force");
  } else {
    a = {"verify", package, "--quiet", "--json", "--threads", threads};
    if (o_.reexecute) a.push_back("--reexecute");
  }
  // The job streams within three quarters of its budget (`run --memory`, at least the 64 MiB
  // it takes), leaving the rest to the program itself: its code and libraries, the report's
  // copies (a run of 12 x 1200x800 under --memory 64M peaked at 70 MB, 120 MB with its
  // report). The batch watches the whole process against the whole budget.
  if (o_.memory > 0 && step != "verify") {
    a.push_back("--memory");
    a.push_back(std::to_string(std::max<std::uint64_t>(kLeastJobBudget, o_.memory / 4 * 3)));
  }
  return a;
}

LedgerEntry Runner::newEntry(const Job& job, const std::string& step) const {
  LedgerEntry e;
  e.capture = job.item.path;
  e.packageItem = job.item.isPackage;
  e.step = step;
  e.attempt = historyOf(ledgerOf(job.item.path), job.item.path, step).nextAttempt();
  e.start = ledgerTime();
  e.memoryBudget = o_.memory;
  e.host = host_;
  e.version = surrogateVersion();
  if (step != "run") e.package = job.package.string();
  return e;
}

bool Runner::settlePackHere(Job& job) {
  const LedgerEntry* known = lastSuccess(job.item.path, "pack");
  const FileState package = packageState(job.package, knownPackage(job.item.path));
  if (!package.exists) return false;
  const FileState carrier = carrierState(job.item.where());
  // Its package of an earlier carrier is packed again; of this one (restored) recorded below.
  if (known && known->packageSha256 == package.sha256 && known->carrierSha256 != carrier.sha256) {
    job.forcePack = true;
    return false;
  }
  LedgerEntry e = newEntry(job, "pack");
  std::string inside;
  std::string problem;
  try {
    const archive::Inventory inv = archive::readPackage(job.package, archive::Limits{});
    const std::string carrierInBag = "data/" + std::string(capture::kCarrierPath);
    if (const auto it = inv.files.find(carrierInBag); it != inv.files.end()) inside = it->second.sha256;
  } catch (const Error& err) {
    problem = err.message();
  }
  e.end = ledgerTime();
  e.carrierSha256 = carrier.sha256;
  if (carrier.exists && !inside.empty() && inside == carrier.sha256) {
    // Made by a pack whose batch ended before it wrote the ledger's line: the same carrier,
    // so the same package; recorded, not made again.
    e.adopted = true;
    e.packageId = archive::packageIdentifier(carrier.sha256);
    e.packageSha256 = package.sha256;
    e.packageSize = package.size;
    e.packageMtimeNs = package.mtimeNs;
    e.message = "found already packed from the capture's carrier as it is (recorded without packing again)";
    ++job.attempts;
    record(e);
    finishStep(job, "pack", "done", &ledger_.entries.back(), e.message);
    return true;
  }
  e.exit = static_cast<int>(ErrorKind::Input);
  e.message = job.package.string() + " exists and is not a package of this capture's carrier as the ledger " +
              "records it" + (problem.empty() ? "" : " (" + problem + ")") +
              "; move it away (or give --packages FOLDER), then run the batch again";
  ++job.attempts;
  record(e);
  finishStep(job, "pack", "failed", &ledger_.entries.back(), e.message);
  return true;
}

void Runner::advance(Job& job) {
  while (!job.child && job.next < o_.steps.size()) {
    const std::string& step = o_.steps[job.next];
    if (!applies(job, step)) {
      ++job.next;
      continue;
    }
    if (job.attempts == 0 || job.recheck) {
      const bool afterWaiting = job.recheck;
      job.recheck = false;
      std::string why;
      if (stillValid(job, step, why)) {
        finishStep(job, step, "skipped", nullptr, "done before and still valid");
        continue;
      }
      if (afterWaiting && step == "run" && processedMeanwhile(job)) {
        finishStep(job, step, "skipped", nullptr, "processed meanwhile by the Surrogate command it waited for");
        continue;
      }
      if (step == "pack" && settlePackHere(job)) continue;
      if (step == "verify" && !packageState(job.package, knownPackage(job.item.path)).exists) {
        LedgerEntry e = newEntry(job, step);
        e.end = ledgerTime();
        e.exit = static_cast<int>(ErrorKind::Input);
        e.message = job.package.string() + " does not exist: pack the capture first (--do pack,verify)";
        ++job.attempts;
        record(e);
        finishStep(job, step, "failed", &ledger_.entries.back(), e.message);
        continue;
      }
    }
    job.entry = newEntry(job, step);
    ++job.attempts;
    job.child = std::make_unique<Child>(program_, commandFor(job, step), o_.memory);
  }
  if (!job.child && job.next >= o_.steps.size()) job.finished = true;
}

void Runner::ended(Job& job) {
  const ChildResult r = job.child->result();
  job.child.reset();
  const std::string step = o_.steps[job.next];
  LedgerEntry e = job.entry;
  e.end = ledgerTime();
  e.seconds = r.seconds;
  e.exit = r.exit;
  e.peakMemory = r.peakMemory;
  e.reexecuted = step == "verify" && o_.reexecute;
  const nlohmann::json report = jsonReport(r.out);
  const bool refused = report.is_object() && report.contains("error") && report["error"].is_object();
  const std::string refusal = refused ? textOf(report["error"], "message") : "";
  // The command's advice ("wait for it to finish, then run this command again") is the batch's
  // to follow, not to print.
  if (!r.overBudget && r.exit == static_cast<int>(ErrorKind::Input) && refused &&
      textOf(report["error"], "step") == capture::kCaptureHeldStep && waitForCapture(job, refusal.substr(0, refusal.find("; ")))) {
    // Another command holds the capture's lock (a review's Apply, a run typed by hand): not an
    // attempt; the job waits and its step is checked again when it comes back.
    --job.attempts;
    job.waiting = true;
    return;
  }
  if (r.overBudget) {
    e.message = "stopped: its memory (" + memorySize(r.peakMemory) + ") passed the budget of " +
                memorySize(o_.memory) + " per job (--memory); give a larger --memory, or fewer --jobs with more memory each";
  } else if (report.is_object() && report.contains("error") && report["error"].is_object()) {
    const std::string file = textOf(report["error"], "file"), message = textOf(report["error"], "message");
    e.message = file.empty() ? message : file + ": " + message;
  } else if (step == "verify" && report.is_object()) {
    e.message = verifyVerdict(r.exit);
    if (r.exit != 0)
      if (const std::string failed = failedChecks(report); !failed.empty()) e.message += ": " + failed;
  } else if (r.exit == 0) {
    e.message = step == "run" ? "processed" : "packed into " + job.package.string();
  } else if (r.exit > 128) {
    e.message = "ended by signal " + std::to_string(r.exit - 128) + (r.err.empty() ? "" : ": " + lastErrorLine(r.err));
  } else {
    e.message = lastErrorLine(r.err);
    if (e.message.empty()) e.message = "ended with exit code " + std::to_string(r.exit);
  }
  if (!r.overBudget && o_.memory > 0 && r.peakMemory > o_.memory)
    // Ended between two looks at its memory: its work stands, and the budget is still named
    // as passed, so that --memory can be set right for the rest of a backlog.
    e.message += " (its memory peaked at " + memorySize(r.peakMemory) + ", above the budget of " +
                 memorySize(o_.memory) + " per job (--memory); it ended before it could be stopped)";
  if (step == "pack" && report.is_object()) e.packageId = textOf(report, "packageId");
  if (step != "verify" && !job.item.isPackage) e.carrierSha256 = carrierState(job.item.where()).sha256;
  if (step != "run") {
    // After a pack the package is new: read whole. After a verify, as the ledger knows it.
    const FileState p = packageState(job.package, step == "pack" ? nullptr : knownPackage(job.item.path));
    e.packageSha256 = p.sha256;
    e.packageSize = p.size;
    e.packageMtimeNs = p.mtimeNs;
    if (step == "verify" && e.packageId.empty())
      if (const LedgerEntry* packed = lastSuccess(job.item.path, "pack")) e.packageId = packed->packageId;
  }
  record(e);
  job.report.workDone = true;
  if (r.exit == 0) return finishStep(job, step, "done", &ledger_.entries.back(), e.message);
  // A budget passed is passed again: no retry. A verification's verdict is the package's.
  const bool retry = !r.overBudget && !(step == "verify" && r.exit >= 1 && r.exit <= 4) &&
                     job.attempts < 1 + std::max(0, o_.retries);
  if (!retry) finishStep(job, step, "failed", &ledger_.entries.back(), e.message);
}

}  // namespace surrogate::batch
