#include "pipeline/stage.h"

#include <algorithm>

#include "core/error.h"

namespace surrogate::pipeline {

NoOptions NoOptions::fromParameters(const Parameters& parameters) {
  if (!parameters.empty())
    throw Error(ErrorKind::Input, parameters.front().first + "=" + parameters.front().second, "carrier",
                "is a parameter of a step that takes none");
  return {};
}

StageRegistry& StageRegistry::instance() {
  static StageRegistry registry;
  return registry;
}

std::function<std::vector<std::string>(const carrier::Step&)> alwaysReads(std::vector<std::string> keys) {
  return [keys = std::move(keys)](const carrier::Step&) { return keys; };
}

void StageRegistry::add(StageInfo info, Factory factory) {
  if (has(info.component))
    throw Error(ErrorKind::Internal, info.component, "pipeline", "is registered twice");
  entries_.push_back({std::move(info), std::move(factory)});
}

void StageRegistry::add(const std::string& component, Factory factory) {
  StageInfo info;
  info.component = component;
  info.version = factory()->version();
  add(std::move(info), std::move(factory));
}

const StageInfo* StageRegistry::info(const std::string& component) const {
  for (const Entry& e : entries_)
    if (e.info.component == component) return &e.info;
  return nullptr;
}

bool StageRegistry::runsAsRecorded(const std::string& component, const std::string& version) const {
  const StageInfo* i = info(component);
  if (!i) return false;
  return version == i->version || std::find(i->alsoRuns.begin(), i->alsoRuns.end(), version) != i->alsoRuns.end();
}

bool StageRegistry::has(const std::string& component) const { return info(component) != nullptr; }

std::unique_ptr<Stage> StageRegistry::create(const std::string& component) const {
  for (const Entry& e : entries_)
    if (e.info.component == component) return e.factory();
  throwInputError("carrier", "pipeline",
                  "names the processing component \"" + component +
                      "\", which this version of Surrogate does not have");
}

std::vector<const StageInfo*> StageRegistry::stages() const {
  std::vector<const StageInfo*> out;
  for (const Entry& e : entries_) out.push_back(&e.info);
  return out;
}

std::vector<std::string> StageRegistry::components() const {
  std::vector<std::string> out;
  for (const Entry& e : entries_) out.push_back(e.info.component);
  return out;
}

}  // namespace surrogate::pipeline
