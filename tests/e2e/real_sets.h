// The real photographs kept in the repository (tests/data/real-rti/SOURCE.md), as the end-to-end
// tests read them: where a set is, a capture made of its images, and PSBox's reference lights,
// read here rather than by Surrogate's own readers (the code under test).
#pragma once

#include <catch2/catch.hpp>

#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include "e2e_support.h"
#include "light_errors.h"

namespace e2e {

inline std::filesystem::path realData(const std::string& set) {
  return std::filesystem::path(SURROGATE_SOURCE_DIR) / "tests/data/real-rti" / set;
}

// A fresh capture (in a folder named after `name`) whose jpeg-exports/ holds the set's images
// (JPG or PNG).
inline std::filesystem::path realCapture(const std::string& set, const std::string& name) {
  namespace fs = std::filesystem;
  const fs::path capture = freshDir(name) / "capture";
  fs::create_directories(capture / "jpeg-exports");
  for (const auto& entry : fs::directory_iterator(realData(set))) {
    const std::string ext = entry.path().extension().string();
    if (ext == ".JPG" || ext == ".png") fs::copy_file(entry.path(), capture / "jpeg-exports" / entry.path().filename());
  }
  return capture;
}

// PSBox's light_directions.txt of `set`: three rows (x, y, z), one column per image, y up.
inline std::vector<Direction> psboxLights(const std::string& set) {
  std::ifstream in(realData(set) / "light_directions.txt");
  std::vector<std::vector<double>> rows;
  for (std::string line; std::getline(in, line);) {
    std::istringstream s(line);
    std::vector<double> row;
    for (double v; s >> v;) row.push_back(v);
    if (!row.empty()) rows.push_back(row);
  }
  REQUIRE(rows.size() == 3);
  REQUIRE(rows[1].size() == rows[0].size());
  REQUIRE(rows[2].size() == rows[0].size());
  std::vector<Direction> out;
  for (std::size_t i = 0; i < rows[0].size(); ++i) out.push_back({rows[0][i], rows[1][i], rows[2][i]});
  return out;
}

}  // namespace e2e
