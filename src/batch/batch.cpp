#include "batch/batch.h"

#include <unistd.h>

#include <algorithm>
#include <deque>
#include <memory>
#include <nlohmann/json.hpp>
#include <thread>
#include <unordered_map>

#include "archive/package.h"
#include "archive/package_reader.h"
#include "batch/jobs.h"
#include "batch/ledger.h"
#include "batch/resume.h"
#include "capture/capture.h"
#include "core/error.h"
#include "core/identity.h"
#include "core/memory_budget.h"
#include "core/version.h"

namespace surrogate::batch {

namespace fs = std::filesystem;

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

namespace {

// The least streaming budget `run --memory` takes.
constexpr std::uint64_t kLeastJobBudget = 64ull << 20;

// The last line of a command's output that is a JSON object (its --json report), parsed; null
// when there is none.
nlohmann::json jsonReport(const std::string& out) {
  std::size_t end = out.size();
  while (end > 0) {
    std::size_t begin = out.rfind('\n', end - 1);
    begin = begin == std::string::npos ? 0 : begin + 1;
    const std::string line = out.substr(begin, end - begin);
    if (!line.empty() && line[0] == '{') {
      nlohmann::json j = nlohmann::json::parse(line, nullptr, false);
      if (j.is_object()) return j;
    }
    if (begin == 0) break;
    end = begin - 1;
  }
  return nullptr;
}

std::string textOf(const nlohmann::json& j, const char* key) {
  return j.is_object() && j.contains(key) && j[key].is_string() ? j[key].get<std::string>() : "";
}

// The last non-empty line of a command's standard error, without "surrogate COMMAND: ".
std::string lastErrorLine(const std::string& err) {
  std::string text = err;
  while (!text.empty() && (text.back() == '\n' || text.back() == '\r')) text.pop_back();
  const std::size_t nl = text.rfind('\n');
  std::string line = nl == std::string::npos ? text : text.substr(nl + 1);
  if (line.rfind("surrogate ", 0) == 0)
    if (const std::size_t colon = line.find(": "); colon != std::string::npos) line = line.substr(colon + 2);
  return line;
}

// verify --json's failed checks as "check: what (where, where, ...)", the files named.
std::string failedChecks(const nlohmann::json& report) {
  std::string out;
  if (!report.contains("checks") || !report["checks"].is_array()) return out;
  for (const nlohmann::json& c : report["checks"]) {
    if (!c.is_object() || !c.contains("passed") || !c["passed"].is_boolean() || c["passed"].get<bool>()) continue;
    std::string one = textOf(c, "name");
    const std::string what = textOf(c, "what");
    if (!what.empty()) one += ": " + what;
    if (c.contains("where") && c["where"].is_array() && !c["where"].empty()) {
      std::string where;
      for (const nlohmann::json& w : c["where"])
        if (w.is_string()) where += (where.empty() ? "" : ", ") + w.get<std::string>();
      one += " (" + where + ")";
    }
    out += (out.empty() ? "" : "; ") + one;
  }
  return out;
}

struct Job {
  WorkItem item;
  fs::path package;
  std::size_t next = 0;        // index into the steps
  int attempts = 0;            // of the current step, in this batch
  bool forcePack = false;
  std::unique_ptr<Child> child;
  LedgerEntry entry;           // the attempt running
  JobReport report;
  bool finished = false;
};

class Runner {
 public:
  Runner(const std::vector<WorkItem>& items, const BatchOptions& options) : items_(items), o_(options) {
    for (const std::string& s : o_.steps)
      if (std::find(kSteps.begin(), kSteps.end(), s) == kSteps.end())
        throw Error(ErrorKind::Usage, "--do " + s, "command line", "is not a step: give run, pack and/or verify");
    program_ = o_.program.empty() ? selfExecutable() : o_.program;
    const int cores = static_cast<int>(std::max(1u, std::thread::hardware_concurrency()));
    threads_ = o_.threadsPerJob > 0 ? o_.threadsPerJob : std::max(1, cores / std::max(1, o_.jobs));
    host_ = hostName();
    requireDistinctPackages(items_, o_.packagesDir);
    if (!o_.dryRun) requireWritableLedger(o_.ledger);
    ledger_ = readLedger(o_.ledger);
    for (std::size_t i = 0; i < ledger_.entries.size(); ++i) byItem_[ledger_.entries[i].capture].push_back(i);
  }

  BatchResult run() {
    BatchResult result;
    result.items = items_.size();
    if (o_.dryRun) {
      for (const WorkItem& item : items_) o_.plan(planOf(item));
      return result;
    }
    std::deque<std::size_t> queue;
    for (std::size_t i = 0; i < items_.size(); ++i) queue.push_back(i);
    std::vector<std::unique_ptr<Job>> active;
    std::size_t finished = 0;
    while (!queue.empty() || !active.empty()) {
      bool changed = false;
      while (static_cast<int>(active.size()) < std::max(1, o_.jobs) && !queue.empty()) {
        auto job = std::make_unique<Job>();
        job->item = items_[queue.front()];
        queue.pop_front();
        job->package = job->item.isPackage ? fs::path(job->item.path) : packagePathFor(job->item.path, o_.packagesDir);
        job->report.item = job->item;
        advance(*job);
        active.push_back(std::move(job));
        changed = true;
      }
      for (auto& job : active)
        if (job->child && job->child->poll()) {
          ended(*job);
          advance(*job);
          changed = true;
        }
      for (auto it = active.begin(); it != active.end();) {
        if (!(*it)->finished) {
          ++it;
          continue;
        }
        const JobReport& r = (*it)->report;
        if (r.succeeded) ++result.succeeded;
        else {
          ++result.failed;
          result.exitCode = std::max(result.exitCode, r.exit > 5 ? 5 : std::max(r.exit, 1));
        }
        if (!r.workDone && r.succeeded) ++result.untouched;
        ++finished;
        if (o_.jobFinished) o_.jobFinished(r);
        if (o_.progress) o_.progress(finished, items_.size());
        it = active.erase(it);
      }
      if (!changed) std::this_thread::sleep_for(kPollInterval);
    }
    return result;
  }

 private:
  // The steps of `o_.steps` that apply to the item (a package has only verify).
  bool applies(const Job& job, const std::string& step) const { return !job.item.isPackage || step == "verify"; }

  // The item's lines, in file order (a copy: a ledger of 100 000 packages is not searched whole
  // for each decision).
  Ledger ledgerOf(const std::string& item) const {
    Ledger l;
    if (const auto it = byItem_.find(item); it != byItem_.end())
      for (std::size_t i : it->second) l.entries.push_back(ledger_.entries[i]);
    return l;
  }

  const LedgerEntry* lastMatching(const std::string& item, const std::function<bool(const LedgerEntry&)>& wanted) const {
    const auto it = byItem_.find(item);
    if (it == byItem_.end()) return nullptr;
    for (auto i = it->second.rbegin(); i != it->second.rend(); ++i)
      if (wanted(ledger_.entries[*i])) return &ledger_.entries[*i];
    return nullptr;
  }

  const LedgerEntry* lastSuccess(const std::string& item, const std::string& step) const {
    return lastMatching(item, [&](const LedgerEntry& e) { return e.step == step && e.succeeded(); });
  }

  // The ledger's record of the package file as it was last seen (by a pack or a verify), so
  // that an unchanged package is not read again.
  const LedgerEntry* knownPackage(const std::string& item) const {
    return lastMatching(item, [](const LedgerEntry& e) { return e.succeeded() && !e.packageSha256.empty(); });
  }

  // Whether the step is done and still valid; `why` says why not.
  bool stillValid(const Job& job, const std::string& step, std::string& why) const {
    const std::string& item = job.item.path;
    const Ledger mine = ledgerOf(item);
    if (step == "run") return runStillValid(historyOf(mine, item, "run"), carrierState(item), why);
    if (step == "pack")
      return packStillValid(historyOf(mine, item, "pack"), carrierState(item),
                            packageState(job.package, knownPackage(item)), why);
    return verifyStillValid(historyOf(mine, item, "verify"), packageState(job.package, knownPackage(item)),
                            o_.reexecute, why);
  }

  ItemPlan planOf(const WorkItem& item) const {
    Job job;
    job.item = item;
    job.package = item.isPackage ? fs::path(item.path) : packagePathFor(item.path, o_.packagesDir);
    ItemPlan plan;
    plan.item = item;
    std::string before;  // an earlier step that will run: the later ones follow it
    for (const std::string& step : o_.steps) {
      if (!applies(job, step)) continue;
      PlannedStep p;
      p.step = step;
      if (step != "run") p.package = job.package.string();
      std::string why;
      if (before.empty() && stillValid(job, step, why)) {
        p.skipped = true;
      } else {
        p.why = before.empty() ? why : "after " + before;
        before = step;
      }
      plan.steps.push_back(p);
    }
    return plan;
  }

  std::vector<std::string> commandFor(const Job& job, const std::string& step) const {
    std::vector<std::string> a;
    const std::string threads = std::to_string(threads_);
    if (step == "run") {
      a = {"run", job.item.path, "--quiet", "--json", "--threads", threads};
      if (o_.noReport) a.push_back("--no-report");
    } else if (step == "pack") {
      a = {"pack", job.item.path, "-o", job.package.string(), "--quiet", "--json", "--threads", threads};
      if (o_.noReport) a.push_back("--no-report");
      if (job.forcePack) a.push_back("--force");
    } else {
      a = {"verify", job.package.string(), "--quiet", "--json", "--threads", threads};
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

  LedgerEntry newEntry(const Job& job, const std::string& step) const {
    LedgerEntry e;
    e.capture = job.item.path;
    e.step = step;
    e.attempt = historyOf(ledgerOf(job.item.path), job.item.path, step).nextAttempt();
    e.start = ledgerTime();
    e.memoryBudget = o_.memory;
    e.host = host_;
    e.version = surrogateVersion();
    if (step != "run") e.package = job.package.string();
    return e;
  }

  void record(LedgerEntry e) {
    appendToLedger(o_.ledger, e);
    byItem_[e.capture].push_back(ledger_.entries.size());
    ledger_.entries.push_back(std::move(e));
  }

  void finishStep(Job& job, const std::string& step, const std::string& outcome, const LedgerEntry* e,
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

  // A step that ends without a child: the pack of a package that exists already.
  // Returns true when it was settled here (adopted or refused).
  bool settlePackHere(Job& job) {
    const LedgerEntry* known = lastSuccess(job.item.path, "pack");
    const FileState package = packageState(job.package, knownPackage(job.item.path));
    if (!package.exists) return false;
    if (known && known->packageSha256 == package.sha256) {
      job.forcePack = true;  // this batch's package of an earlier state of the capture
      return false;
    }
    const FileState carrier = carrierState(job.item.path);
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

  // Starts the job's next step that is not done, or finishes the job.
  void advance(Job& job) {
    while (!job.child && job.next < o_.steps.size()) {
      const std::string& step = o_.steps[job.next];
      if (!applies(job, step)) {
        ++job.next;
        continue;
      }
      if (job.attempts == 0) {
        std::string why;
        if (stillValid(job, step, why)) {
          finishStep(job, step, "skipped", nullptr, "done before and still valid");
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

  // The step's child has ended: its line in the ledger, then a retry or the next step.
  void ended(Job& job) {
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
    if (step != "verify" && !job.item.isPackage) e.carrierSha256 = carrierState(job.item.path).sha256;
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
    if (r.exit == 0) {
      finishStep(job, step, "done", &ledger_.entries.back(), e.message);
      job.report.workDone = true;
      return;
    }
    job.report.workDone = true;
    // A budget passed is passed again: no retry. A verification's verdict is the package's.
    const bool retry = !r.overBudget && !(step == "verify" && r.exit >= 1 && r.exit <= 4) &&
                       job.attempts < 1 + std::max(0, o_.retries);
    if (!retry) finishStep(job, step, "failed", &ledger_.entries.back(), e.message);
  }

  const std::vector<WorkItem>& items_;
  const BatchOptions& o_;
  std::string program_, host_;
  int threads_ = 1;
  Ledger ledger_;
  std::unordered_map<std::string, std::vector<std::size_t>> byItem_;  // positions in ledger_.entries
};

}  // namespace

BatchResult runBatch(const std::vector<WorkItem>& items, const BatchOptions& options) {
  Runner runner(items, options);
  return runner.run();
}

}  // namespace surrogate::batch
