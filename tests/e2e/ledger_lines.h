// Private to tests/e2e: a batch ledger read as its JSON lines, for the batch tests.
#pragma once

#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

namespace e2e {

// Every line of the ledger parsed (a torn line fails the test with json's exception).
inline std::vector<nlohmann::json> ledgerLines(const std::filesystem::path& ledger) {
  std::vector<nlohmann::json> out;
  std::ifstream in(ledger);
  std::string line;
  while (std::getline(in, line)) out.push_back(nlohmann::json::parse(line));
  return out;
}

}  // namespace e2e
