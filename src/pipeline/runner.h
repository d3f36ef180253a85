// Runs a carrier's process list.
//
// For each step in order: the registered component runs with the step's parameters; its
// result (status, start and end times, duration) goes into the data section and a timing
// entry into the log; the carrier is saved after each step (when a path is given; see Saves),
// so a run that fails leaves a carrier recording what was done and which step failed, never one
// that looks complete. A save is validated and written while the next step runs (one at a
// time, in order); the runner returns, or throws, only once the last is on disk. After each
// step, the shared data that no later step reads (StageInfo::reads) is let go: the decoded
// photographs are freed once the last fit has read them, not held through the derived maps. Steps of a stage that declares no reads keep everything until
// they have run. Work a step left for later (Context::defer: the decoded images' pixel
// digests) is finished and recorded before each save, before the data it reads is let go, and
// before the runner returns.
//
//   Context ctx(capture, carrier, settings);
//   runProcess(ctx, capture / "assembly-files/carrier.xml");
#pragma once

#include <cstddef>
#include <filesystem>

#include "pipeline/context.h"

namespace surrogate::pipeline {

// Which saves the runner makes: after every step (a re-execution: the carrier on disk is the
// record, and one that fails must say how far it got), or only a failed step's, the caller
// saving the carrier once when all succeeded, with what it adds (run: its carrier is staged and
// discarded unless the whole run succeeds, so a save between steps was read by nothing, and
// cost about 2 ms of CPU each: the text made, validated, written and flushed).
enum class Saves { EachStep, FailureOnly };

// Runs the first `steps` steps of the process list (all by default); the others keep no result.
void runProcess(Context& context, const std::filesystem::path& carrierPath,
                std::size_t steps = static_cast<std::size_t>(-1), Saves saves = Saves::EachStep);

}  // namespace surrogate::pipeline
