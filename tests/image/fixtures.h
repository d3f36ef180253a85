// Shared helpers of the src/image tests: fixture paths, scratch folders, and the check that a
// call fails with an Input error naming the file.
#pragma once

#include <catch2/catch.hpp>

#include <filesystem>
#include <string>

#include "core/error.h"

namespace surrogate::test {

inline std::filesystem::path fixture(const std::string& name) {
  return std::filesystem::path(SURROGATE_SOURCE_DIR) / "tests/data" / name;
}

// A fresh, empty folder under the system temp folder, unique to the test name.
inline std::filesystem::path scratchDir(const std::string& name) {
  const auto dir = std::filesystem::temp_directory_path() / ("surrogate-test-image-" + name);
  std::filesystem::remove_all(dir);
  std::filesystem::create_directories(dir);
  return dir;
}

// Runs `call`, requires an Error(Input) naming `file`, and returns its message.
template <typename Call>
std::string inputErrorOf(const std::filesystem::path& file, Call&& call) {
  try {
    call();
  } catch (const Error& e) {
    CHECK(e.kind() == ErrorKind::Input);
    CHECK(e.file() == file.string());
    CHECK_FALSE(e.message().empty());
    return e.message();
  }
  FAIL("no error for " << file);
  return {};
}

}  // namespace surrogate::test
