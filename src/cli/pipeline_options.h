// The options of `surrogate run` (also accepted by `lights` and `pack`), and their
// translation into a RunRequest: stage parameters and recorded human interventions.
#pragma once

#include <vector>

#include "cli/args.h"
#include "cli/progress.h"
#include "pipeline/context.h"
#include "run/plan.h"

namespace surrogate::cli {

// Options that shape what the pipeline does (recorded in the carrier). `withFit` adds --basis.
std::vector<OptionSpec> pipelineOptions(bool withFit);
// The same with the fit's options, for a command that runs the pipeline when needed (pack,
// audit): its --help lists them after its own.
std::vector<OptionSpec> runOptionsForAnotherCommand();
// Options that shape how it runs (not recorded): --threads, --memory, --quiet, --verbose, --json.
std::vector<OptionSpec> runtimeOptions();

run::RunRequest requestFrom(const Args& args);
pipeline::RunSettings settingsFrom(const Args& args);
// The same, reporting progress on `bar`.
pipeline::RunSettings settingsFrom(const Args& args, ProgressBar& bar);

}  // namespace surrogate::cli
