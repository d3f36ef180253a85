// Test support: a small capture folder with a carrier made through the carrier API (no
// pipeline): originals, exports, a sidecar, assembly and result files, two steps with
// parameters, an intervention, results and log entries, user metadata.
#pragma once

#include <filesystem>

namespace samplecapture {

// Writes the capture under `dir` (created) and returns it.
std::filesystem::path make(const std::filesystem::path& dir);

}  // namespace samplecapture
