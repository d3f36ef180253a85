// The state a pipeline run shares between its stages.
//
// `carrier` is the provenance document being built (or re-executed). `blackboard` caches data
// derived from the carrier's files that is too large for the carrier itself (decoded pixel
// stacks); each entry is recomputed by running the process list from the start, so the carrier
// stays the single source of truth.
#pragma once

#include <any>
#include <cstddef>
#include <filesystem>
#include <functional>
#include <map>
#include <memory>
#include <string>

#include "carrier/carrier.h"
#include "core/error.h"

namespace surrogate::pipeline {

// What the user asked of the run (not recorded as parameters: they do not change results).
struct RunSettings {
  int threads = 0;                                // 0 = all cores
  std::size_t memoryBudget = std::size_t(2) << 30;  // bytes: the process's peak should stay below
  // The part of memoryBudget one fit may use (its output model and its row bands): three
  // quarters. The rest is for what the process holds besides: models kept for the derived maps,
  // decoders' buffers, the carrier (measured: 60 x 24 Mpx, pipeline_bench).
  std::size_t fitBudget() const { return memoryBudget / 4 * 3; }
  std::string who;                                // the person running it (interventions, log)
  // Called with (step label, fraction done 0..1) for progress display; may be empty.
  std::function<void(const std::string&, double)> progress;
};

class Context {
 public:
  Context(std::filesystem::path captureRoot, carrier::Carrier& carrier, RunSettings settings)
      : capture(std::move(captureRoot)), carrier(carrier), settings(std::move(settings)) {}

  std::filesystem::path capture;  // absolute capture folder
  carrier::Carrier& carrier;
  RunSettings settings;

  // Absolute path of a file the carrier lists by id.
  std::filesystem::path pathOf(const std::string& fileId) const;

  template <typename T>
  void put(const std::string& key, std::shared_ptr<T> value) {
    blackboard_[key] = std::move(value);
  }
  // The cached value, or Error(Internal) naming the missing key (a process list in the wrong
  // order, e.g. fitting before decoding).
  template <typename T>
  std::shared_ptr<T> get(const std::string& key) const {
    auto it = blackboard_.find(key);
    if (it == blackboard_.end())
      throw Error(ErrorKind::Input, "carrier", "pipeline",
                  "a step needs \"" + key + "\", which no earlier step of the process list "
                  "produced; the process list is incomplete or out of order");
    return std::any_cast<std::shared_ptr<T>>(it->second);
  }
  bool has(const std::string& key) const { return blackboard_.count(key) != 0; }

  void progress(const std::string& label, double fraction) const {
    if (settings.progress) settings.progress(label, fraction);
  }

 private:
  std::map<std::string, std::any> blackboard_;
};

}  // namespace surrogate::pipeline
