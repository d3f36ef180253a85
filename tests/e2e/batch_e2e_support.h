// What the batch end-to-end tests share (test_batch_e2e.cpp, test_batch_concurrent_e2e.cpp,
// test_verify_batch_e2e.cpp, test_batch_schedulers_e2e.cpp): generated captures and their
// list, the ledger's lines counted, a file's SHA-256, the program's version, and the processes
// a batch started.
#pragma once

#include <cstddef>
#include <filesystem>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "ledger_lines.h"

namespace batch_e2e {

using e2e::ledgerLines;

// `count` captures of 6 images at 200x150 in `dir` (cap1, cap2, ...), and the list naming them.
std::filesystem::path makeCaptures(const std::filesystem::path& dir, int count, int images = 6, int width = 200,
                                   int height = 150);

// The ledger lines of `capture`'s `step` that ended with `exit`.
std::size_t count(const std::vector<nlohmann::json>& lines, const std::string& capture, const std::string& step,
                  int exit);

// The file's SHA-256, in hex.
std::string sha(const std::filesystem::path& p);

// The version `surrogate --version` says ("0.1.0").
std::string version();

// Processes whose command line names `text` (the jobs of a batch in a test's own folder).
std::vector<int> processesNaming(const std::string& text);

}  // namespace batch_e2e
