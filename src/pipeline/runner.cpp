#include "pipeline/runner.h"

#include <chrono>
#include <cstdio>
#include <exception>
#include <future>
#include <mutex>
#include <set>
#include <vector>

#include "carrier/carrier.h"
#include "pipeline/stage.h"

namespace surrogate::pipeline {

namespace fs = std::filesystem;

fs::path Context::pathOf(const std::string& fileId) const {
  const carrier::FileRecord* f = carrier.findFile(fileId);
  if (!f) throwInputError("carrier", "pipeline", "refers to file id " + fileId + ", which it does not list");
  const bool output = f->role == "assembly" || f->role == "result";
  return (output ? outputRoot : capture) / f->path;
}

namespace {

// The step's parameters read by its stage's options struct before it runs: a bad value (not a
// number, out of range, an unknown name) is an Error naming it, recorded as the step's failure.
void checkParameters(const carrier::Step& step) {
  const StageInfo* info = StageRegistry::instance().info(step.component);
  if (!info || !info->check) return;
  Parameters params;
  for (const carrier::Param& p : step.params) params.emplace_back(p.name, p.value);
  info->check(params);
}

// A step's progress as the user sees it: each part of a step (a label) ends at 100 % when the
// step moves on to its next part or completes, so that no bar is left part-way for work that
// is done (a stage reports its start and its own milestones; the end is the runner's to say).
class StepProgress {
 public:
  explicit StepProgress(std::function<void(const std::string&, double)> out) : out_(std::move(out)) {}
  void update(const std::string& label, double fraction) {
    std::lock_guard<std::mutex> lock(mutex_);
    if (label != label_) completeLocked();
    label_ = label;
    done_ = fraction >= 1;
    out_(label, fraction);
  }
  // The step succeeded: its last part is done.
  void complete() {
    std::lock_guard<std::mutex> lock(mutex_);
    completeLocked();
  }

 private:
  void completeLocked() {
    if (!label_.empty() && !done_) out_(label_, 1);
    done_ = true;
  }
  std::function<void(const std::string&, double)> out_;
  std::mutex mutex_;
  std::string label_;
  bool done_ = true;
};

// Routes the stages' progress through `progress` while a step runs, however it ends.
class ProgressRouting {
 public:
  ProgressRouting(RunSettings& settings, StepProgress& progress)
      : settings_(settings), saved_(settings.progress) {
    if (saved_) settings_.progress = [&progress](const std::string& label, double f) { progress.update(label, f); };
  }
  ~ProgressRouting() { settings_.progress = saved_; }
  ProgressRouting(const ProgressRouting&) = delete;
  ProgressRouting& operator=(const ProgressRouting&) = delete;

 private:
  RunSettings& settings_;
  std::function<void(const std::string&, double)> saved_;
};

// Lets go of every value of the blackboard that no step of `later` reads; nothing while one
// of them may read anything (a stage without StageInfo::reads, or a step whose parameters do
// not say: they are refused when that step runs, with the step named).
void releaseUnread(Context& context, const std::vector<carrier::Step>& later) {
  std::set<std::string> read;
  for (const carrier::Step& step : later) {
    const StageInfo* info = StageRegistry::instance().info(step.component);
    if (!info || !info->reads) return;
    try {
      for (std::string& key : info->reads(step)) read.insert(std::move(key));
    } catch (const Error&) {
      return;
    }
  }
  for (const std::string& key : context.keys())
    if (!read.count(key)) context.release(key);
}

// The carrier saved after each step without holding the next step up: the text is made at once
// (the carrier changes as soon as the next step starts), then validated and written atomically
// (fsync, rename) on a thread of its own while the next step runs: about 2 ms of CPU and 2 ms
// of waiting for the disk per step on the machines this project measures on (perf, strace
// -T). Saves happen in order, each after the one before it is on disk, so the carrier on disk
// is always one the run saved; wait() (before the runner returns or saves a failure) leaves
// none pending and rethrows a save's error.
class CarrierSaver {
 public:
  explicit CarrierSaver(fs::path path) : path_(std::move(path)) {}
  ~CarrierSaver() {
    // Leaving by an exception: its error is the one reported, the save's is dropped.
    if (pending_.valid()) try {
        pending_.get();
      } catch (...) {
      }
  }
  CarrierSaver(const CarrierSaver&) = delete;
  CarrierSaver& operator=(const CarrierSaver&) = delete;

  void save(const carrier::Carrier& c) {
    if (path_.empty()) return;
    std::string text = carrier::toXml(c);
    wait();
    pending_ = std::async(std::launch::async, [this, text = std::move(text)] { carrier::saveCarrierXml(text, path_); });
  }
  void wait() {
    if (pending_.valid()) pending_.get();
  }

 private:
  fs::path path_;
  std::future<void> pending_;
};

}  // namespace

void runProcess(Context& context, const fs::path& carrierPath, std::size_t steps, Saves saves) {
  carrier::Carrier& c = context.carrier;
  CarrierSaver saver(carrierPath);
  auto save = [&] {
    context.finishDeferred();
    c.header.modified = carrier::timestampNow();
    saver.save(c);
  };
  // Copy the list: a stage may append files, never steps, but the reference must stay valid.
  std::vector<carrier::Step> list = c.process;
  if (steps < list.size()) list.resize(steps);
  const auto userProgress = context.settings.progress;
  for (std::size_t k = 0; k < list.size(); ++k) {
    const carrier::Step& step = list[k];
    StepProgress progress(userProgress);
    const ProgressRouting routing(context.settings, progress);
    std::unique_ptr<Stage> stage = StageRegistry::instance().create(step.component);
    c.clearResult(step.id);
    carrier::Result result;
    result.step = step.id;
    result.started = carrier::timestampNow();
    const auto t0 = std::chrono::steady_clock::now();
    auto fail = [&](const Error& e) {
      result.status = "failed";
      result.ended = carrier::timestampNow();
      result.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
      c.data.push_back(result);
      c.addLog("error", step.id, e.what());
      // What earlier steps left for later is recorded as if they had done it; its own failure
      // (it only computes) must not hide the step's.
      try {
        context.finishDeferred();
      } catch (...) {
      }
      save();
      saver.wait();
    };
    try {
      checkParameters(step);
      stage->run(step, context, result);
    } catch (const Error& e) {
      fail(e);
      throw;
    } catch (const std::exception& e) {
      // Stages throw only Error; anything else is a bug, recorded as the step's failure all the
      // same, so that no carrier looks complete after it.
      const Error internal(ErrorKind::Internal, "carrier", step.component,
                           std::string("step ") + step.id + " failed unexpectedly (" + e.what() +
                               "); this is a bug in Surrogate, please report it");
      fail(internal);
      throw internal;
    }
    progress.complete();
    result.ended = carrier::timestampNow();
    result.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    c.data.push_back(std::move(result));
    char seconds[32];
    std::snprintf(seconds, sizeof seconds, "%.3f", c.data.back().seconds);
    c.addLog("timing", step.id, step.component + " completed in " + seconds + " s");
    if (saves == Saves::EachStep) save();
    releaseUnread(context, std::vector<carrier::Step>(list.begin() + k + 1, list.end()));
  }
  context.finishDeferred();
  saver.wait();
}

}  // namespace surrogate::pipeline
