#include "batch/batch.h"

#include <fcntl.h>
#include <sys/file.h>
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <deque>
#include <memory>
#include <nlohmann/json.hpp>
#include <optional>
#include <set>
#include <thread>
#include <unordered_map>

#include "archive/package.h"
#include "archive/package_reader.h"
#include "batch/jobs.h"
#include "batch/ledger.h"
#include "batch/resume.h"
#include "batch/step_output.h"
#include "capture/capture.h"
#include "capture/lock.h"
#include "carrier/carrier.h"
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

// A job whose capture another Surrogate command holds looks again after this long, and gives
// up (the refusal recorded as the step's failure) after kBusyWaitLimit: a lock is held by a
// live process only (flock), so the wait is for work being done, a 24 Mpx capture's run, pack
// and verify in about a minute.
constexpr std::chrono::seconds kBusyRetryInterval{1};
constexpr std::chrono::minutes kBusyWaitLimit{30};

// The least streaming budget `run --memory` takes.
constexpr std::uint64_t kLeastJobBudget = 64ull << 20;

// A batch's claim on a capture folder, held from its job's first step to its last step's
// ledger line: a second batch on the same list (a rerun while the first still runs, another
// Slurm task) finds the capture claimed and comes back later, rather than taking the capture's
// lock in the moment between a step's end and its ledger line and doing the step again. An
// exclusive flock() of CAPTURE/.surrogate/batch-claim, apart from the lock each step's command
// takes itself; it goes with the process.
class CaptureClaim {
 public:
  enum class Outcome { Claimed, HeldByAnother, NotAClaimableFolder };

  Outcome claim(const fs::path& capture) {
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

  void release() {
    if (fd_ >= 0) ::close(fd_);
    fd_ = -1;
  }

  CaptureClaim() = default;
  CaptureClaim(const CaptureClaim&) = delete;
  CaptureClaim& operator=(const CaptureClaim&) = delete;
  ~CaptureClaim() { release(); }

 private:
  int fd_ = -1;
};

struct Job {
  WorkItem item;
  CaptureClaim claim;          // a capture item's, while the job is active
  fs::path package;
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
    requireDistinctPackages(items_, o_.packagesDir, o_.packageFormat);
    if (!o_.dryRun) requireWritableLedger(o_.ledger);
    ledgerOffset_ = readLedgerSince(o_.ledger, 0, ledger_);
    for (std::size_t i = 0; i < ledger_.entries.size(); ++i) byItem_[ledger_.entries[i].capture].push_back(i);
  }

  BatchResult run() {
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
  fs::path packageOf(const WorkItem& item) const {
    return item.isPackage ? fs::path(item.where()) : packagePathFor(item.where(), o_.packagesDir, o_.packageFormat);
  }

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
    const std::string& item = job.item.path;  // the ledger's name of it; the files are at where()
    const Ledger mine = ledgerOf(item);
    if (step == "run") return runStillValid(historyOf(mine, item, "run"), carrierState(job.item.where()), why);
    if (step == "pack")
      return packStillValid(historyOf(mine, item, "pack"), carrierState(job.item.where()),
                            packageState(job.package, knownPackage(item)), why);
    return verifyStillValid(historyOf(mine, item, "verify"), packageState(job.package, knownPackage(item)),
                            o_.reexecute, why);
  }

  ItemPlan planOf(const WorkItem& item) const {
    Job job;
    job.item = item;
    job.package = packageOf(item);
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

  LedgerEntry newEntry(const Job& job, const std::string& step) const {
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

  void record(LedgerEntry e) {
    appendToLedger(o_.ledger, e);
    ownUnread_.insert(ownKey(e));
    byItem_[e.capture].push_back(ledger_.entries.size());
    ledger_.entries.push_back(std::move(e));
  }

  // An entry as this batch knows its own: the item, step and start time (milliseconds) on this
  // host.
  static std::string ownKey(const LedgerEntry& e) {
    return e.capture + '\n' + e.step + '\n' + e.start + '\n' + e.host + '\n' + std::to_string(e.attempt);
  }

  // The lines appended to the ledger since this batch last read it, its own aside (record()
  // has them already).
  void refreshLedger() {
    Ledger fresh;
    ledgerOffset_ = readLedgerSince(o_.ledger, ledgerOffset_, fresh);
    for (LedgerEntry& e : fresh.entries) {
      if (const auto own = ownUnread_.find(ownKey(e)); own != ownUnread_.end()) {
        ownUnread_.erase(own);
        continue;
      }
      byItem_[e.capture].push_back(ledger_.entries.size());
      ledger_.entries.push_back(std::move(e));
    }
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

  // The capture is busy (claimed by another batch, or locked by another command): whether the
  // job may wait for it, kBusyRetryInterval between looks, up to kBusyWaitLimit from the first
  // time; after that the refusal is recorded as the step's failure. Its step is checked again
  // when it comes back: the other may have done it.
  bool waitForCapture(Job& job, const std::string& why) const {
    const auto now = std::chrono::steady_clock::now();
    if (!job.busySince) {
      job.busySince = now;
      job.busySinceUtc = carrier::timestampNow();
      if (o_.waiting) o_.waiting(job.item, why);
    }
    job.recheck = true;
    return now - *job.busySince < kBusyWaitLimit;
  }

  // Whether the capture's carrier records a completed run that ended after the job found the
  // capture busy: the command it waited for processed it (another batch's run, whose ledger
  // line may still be on its way, or a review's Apply), and running it again would only add
  // a run to its history. A pack it waited for is recognised by its package (settlePackHere).
  bool processedMeanwhile(const Job& job) const {
    try {
      const carrier::Carrier c = carrier::loadCarrier(fs::path(job.item.where()) / capture::kCarrierPath);
      for (auto r = c.header.runs.rbegin(); r != c.header.runs.rend(); ++r)
        if (r->command == "run") return r->outcome == "completed" && r->ended >= job.busySinceUtc;
    } catch (const Error&) {
      // No carrier, or one this version cannot read: the run step runs and says what is wrong.
    }
    return false;
  }

  // A step that ends without a child: the pack of a package that exists already.
  // Returns true when it was settled here (adopted or refused).
  bool settlePackHere(Job& job) {
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

  // Starts the job's next step that is not done, or finishes the job.
  void advance(Job& job) {
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

  const std::vector<WorkItem>& items_;
  const BatchOptions& o_;
  std::string program_, host_;
  int threads_ = 1;
  Ledger ledger_;
  std::uint64_t ledgerOffset_ = 0;           // where the last read of the ledger ended
  std::multiset<std::string> ownUnread_;     // lines this batch wrote that it has not read back
  std::unordered_map<std::string, std::vector<std::size_t>> byItem_;  // positions in ledger_.entries
};

}  // namespace

BatchResult runBatch(const std::vector<WorkItem>& items, const BatchOptions& options) {
  Runner runner(items, options);
  return runner.run();
}

}  // namespace surrogate::batch
