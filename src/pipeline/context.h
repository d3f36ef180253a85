// The state a pipeline run shares between its stages.
//
// `carrier` is the provenance document being built (or re-executed). `blackboard` caches data
// derived from the carrier's files that is too large for the carrier itself (decoded pixel
// stacks); each entry is recomputed by running the process list from the start, so the carrier
// stays the single source of truth.
#pragma once

#include <algorithm>
#include <any>
#include <cstddef>
#include <filesystem>
#include <functional>
#include <map>
#include <memory>
#include <set>
#include <string>
#include <vector>

#include "carrier/carrier.h"
#include "core/deferred_tasks.h"
#include "core/error.h"
#include "core/image.h"
#include "core/parallel.h"

namespace surrogate::formats {
struct PtmFile;
struct HshFile;
}  // namespace surrogate::formats

namespace surrogate::pipeline {

// What the user asked of the run (not recorded as parameters: they do not change results).
struct RunSettings {
  int threads = 0;                                // 0 = all cores
  std::size_t memoryBudget = std::size_t(2) << 30;  // bytes: the process's peak should stay below
  // Bytes held for the rest of the run out of memoryBudget: the decoded stacks when they are
  // kept in memory (stages::decodeImages). What streams in bands shares what is left.
  std::size_t heldBytes = 0;
  std::size_t streamingBudget() const { return memoryBudget - std::min(heldBytes, memoryBudget); }
  // The part of the streaming budget one fit may use (its output model and its row bands):
  // three quarters. The rest is for what the process holds besides: models kept for the
  // derived maps, decoders' buffers, the carrier (measured: 60 x 24 Mpx, pipeline_bench).
  std::size_t fitBudget() const { return streamingBudget() / 4 * 3; }
  std::string who;                                // the person running it (interventions, log)
  // Called with (step label, fraction done 0..1) for progress display; may be empty.
  std::function<void(const std::string&, double)> progress;
  // Called with each picture a step has written (stages::writePicture): its path relative to
  // the capture and the pixels its PNG holds. May be empty; called from any thread, after the
  // file is complete. surrogate run keeps display copies of them for its report.
  std::function<void(const std::string&, const Image&)> pictureWritten;
  // The same for each fitted model a step has written (.ptm or .rti): its path and the model
  // the file holds. surrogate run makes the report's interactive copies of them. Called on a
  // thread of the step's own while the step writes the file, one call at a time.
  std::function<void(const std::string&, const formats::PtmFile&)> ptmWritten;
  std::function<void(const std::string&, const formats::HshFile&)> hshWritten;
};

class Context {
 public:
  Context(std::filesystem::path captureRoot, carrier::Carrier& carrier, RunSettings settings)
      : capture(std::move(captureRoot)), outputRoot(capture), carrier(carrier),
        settings(std::move(settings)) {}

  std::filesystem::path capture;     // absolute capture folder: where the inputs are read
  // Where the steps write their outputs (assembly-files/, finished-files/ beneath it): the
  // capture itself, or a staging folder that becomes the capture's state only when the whole
  // run succeeded (run/run_commit.h), so a failed run never replaces good results.
  std::filesystem::path outputRoot;
  carrier::Carrier& carrier;
  RunSettings settings;
  // The capture's record before this run (null on a first run or a re-execution): what the
  // ingest compares the originals with, since an original once recorded is evidence.
  const carrier::Carrier* previous = nullptr;

  // Absolute path of a file the carrier lists by id (outputs of this run under outputRoot).
  std::filesystem::path pathOf(const std::string& fileId) const;
  // Absolute path where a step writes the output `relativePath` (relative to the capture).
  std::filesystem::path outputPath(const std::string& relativePath) const {
    return outputRoot / relativePath;
  }

  template <typename T>
  void put(const std::string& key, std::shared_ptr<T> value) {
    blackboard_[key] = std::move(value);
    released_.erase(key);
  }
  // The cached value. Error(Input) naming the key when no earlier step put it (a process list
  // in the wrong order, e.g. fitting before decoding); Error(Internal) naming the key when it
  // holds another type than asked for (a bug: two stages disagree on what the key means).
  template <typename T>
  std::shared_ptr<T> get(const std::string& key) const {
    auto it = blackboard_.find(key);
    if (it == blackboard_.end() && released_.count(key))
      throw Error(ErrorKind::Internal, key, "pipeline",
                  "a step reads shared data its stage does not list in StageInfo::reads, and the "
                  "runner has let go of it; this is a bug in Surrogate, please report it");
    if (it == blackboard_.end())
      throw Error(ErrorKind::Input, "carrier", "pipeline",
                  "a step needs \"" + key + "\", which no earlier step of the process list "
                  "produced; the process list is incomplete or out of order");
    if (const auto* value = std::any_cast<std::shared_ptr<T>>(&it->second)) return *value;
    throw Error(ErrorKind::Internal, key, "pipeline",
                "a step reads the shared data \"" + key + "\" as another type than the step "
                "that put it there; this is a bug in Surrogate, please report it");
  }
  bool has(const std::string& key) const { return blackboard_.count(key) != 0; }
  // Lets go of the value under `key` (freed once nothing else holds it); the runner does this
  // when no later step reads it.
  void release(const std::string& key) {
    if (!blackboard_.erase(key)) return;
    released_.insert(key);
    for (const Deferred& d : deferred_)
      if (std::none_of(d.holding.begin(), d.holding.end(), [&](const std::string& k) { return has(k); })) {
        finishDeferred();
        break;
      }
  }
  std::vector<std::string> keys() const {
    std::vector<std::string> out;
    for (const auto& [key, value] : blackboard_) out.push_back(key);
    return out;
  }

  void progress(const std::string& label, double fraction) const {
    if (settings.progress) settings.progress(label, fraction);
  }

  // Work a step leaves for later (core/deferred_tasks.h), and `record`, which writes its
  // results into the carrier: the step records a placeholder where each result goes, so that
  // the carrier's text is the same whoever ran the work and when. Later steps run it beside a
  // part of their own that keeps one thread busy (besideOneThread); the runner finishes and
  // records it before it saves the carrier or returns, so no saved carrier lacks a result.
  // `holding`: the keys whose data the work reads (it holds a reference): it is finished
  // before the last of them is let go, so that the memory is freed when the runner frees it.
  void defer(std::vector<std::function<void()>> tasks, std::function<void()> record,
             std::vector<std::string> holding) {
    deferred_.push_back({std::make_unique<DeferredTasks>(std::move(tasks)), std::move(record), std::move(holding)});
  }
  // Runs `work`, a part of a step that uses one thread (a library's search), with deferred work
  // on another thread meanwhile; with one thread to run on (settings.threads), only `work`.
  void besideOneThread(const std::function<void()>& work) {
    if (deferred_.empty() || effectiveThreads(settings.threads) < 2) return work();
    deferred_.front().work->besides(work);  // the oldest work: one other thread is all there is
  }
  // Finishes the deferred work on settings.threads threads and records it, in the order
  // deferred; rethrows the first error.
  void finishDeferred() {
    std::vector<Deferred> all = std::move(deferred_);
    deferred_.clear();
    for (Deferred& d : all) {
      d.work->finish(settings.threads);
      d.record();
    }
  }

 private:
  struct Deferred {
    std::unique_ptr<DeferredTasks> work;
    std::function<void()> record;
    std::vector<std::string> holding;
  };
  std::vector<Deferred> deferred_;
  std::map<std::string, std::any> blackboard_;
  std::set<std::string> released_;  // keys let go of, for get's message
};

}  // namespace surrogate::pipeline
