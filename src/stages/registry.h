// The analysis stages after decoding (light estimation, fitting, derived maps): their
// registration, default parameters and descriptions, and the default plan of a run.
#pragma once

#include <string>
#include <utility>
#include <vector>

#include "pipeline/stage.h"

namespace surrogate::stages {

void registerAnalysisStages(pipeline::StageRegistry& registry);

// The parameters a step of `component` gets when the user gives none (its options struct's
// defaults), so the carrier records every value that was used.
std::vector<std::pair<std::string, std::string>> defaultParameters(const std::string& component);

// One sentence for the carrier's <description>.
std::string describeStage(const std::string& component);

}  // namespace surrogate::stages
