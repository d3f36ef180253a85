#include "stages/registry.h"

#include "stages/plan.h"

namespace surrogate::stages {

void registerAnalysisStages(pipeline::StageRegistry&) {}

std::vector<std::pair<std::string, std::string>> defaultParameters(const std::string&) {
  return {};
}

std::vector<std::string> defaultStages(bool) { return {}; }

}  // namespace surrogate::stages
