// Runs a carrier's process list.
//
// For each step in order: the registered component runs with the step's parameters; its
// result (status, start and end times, duration) goes into the data section and a timing
// entry into the log; the carrier is saved after each step (when a path is given), so a run
// that fails leaves a carrier recording what was done and which step failed, never one that
// looks complete.
//
//   Context ctx(capture, carrier, settings);
//   runProcess(ctx, capture / "assembly-files/carrier.xml");
#pragma once

#include <cstddef>
#include <filesystem>

#include "pipeline/context.h"

namespace surrogate::pipeline {

// Runs the first `steps` steps of the process list (all by default); the others keep no result.
void runProcess(Context& context, const std::filesystem::path& carrierPath,
                std::size_t steps = static_cast<std::size_t>(-1));

}  // namespace surrogate::pipeline
