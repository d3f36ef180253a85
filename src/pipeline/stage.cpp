#include "pipeline/stage.h"

#include "core/error.h"

namespace surrogate::pipeline {

StageRegistry& StageRegistry::instance() {
  static StageRegistry registry;
  return registry;
}

void StageRegistry::add(const std::string& component, Factory factory) {
  factories_.emplace_back(component, std::move(factory));
}

bool StageRegistry::has(const std::string& component) const {
  for (const auto& [name, factory] : factories_)
    if (name == component) return true;
  return false;
}

std::unique_ptr<Stage> StageRegistry::create(const std::string& component) const {
  for (const auto& [name, factory] : factories_)
    if (name == component) return factory();
  throwInputError("carrier", "pipeline",
                  "names the processing component \"" + component +
                      "\", which this version of Surrogate does not have");
}

std::vector<std::string> StageRegistry::components() const {
  std::vector<std::string> out;
  for (const auto& [name, factory] : factories_) out.push_back(name);
  return out;
}

}  // namespace surrogate::pipeline
