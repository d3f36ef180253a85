// The stages this build of Surrogate has. The plan (run/plan.h), the carrier's process list
// and the verifier's re-execution all take their stages from the pipeline's registry, which
// this fills.
#pragma once

namespace surrogate::stages {

// Registers every stage this build of Surrogate has with the pipeline's registry (once):
// src/stages/registry.cpp, one line a stage.
void registerBuiltinStages();

}  // namespace surrogate::stages
