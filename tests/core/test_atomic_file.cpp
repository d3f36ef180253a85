#include <catch2/catch.hpp>

#include <filesystem>
#include <fstream>

#include "core/atomic_file.h"
#include "core/error.h"

using namespace surrogate;
namespace fs = std::filesystem;

TEST_CASE("an uncommitted AtomicFile leaves nothing under either name") {
  const fs::path dir = fs::temp_directory_path() / "surrogate-test-atomic";
  fs::remove_all(dir);
  fs::create_directories(dir);
  const fs::path target = dir / "out.txt";
  fs::path temp;
  {
    AtomicFile f(target);
    temp = f.tempPath();
    std::ofstream(temp) << "partial";
  }
  CHECK_FALSE(fs::exists(target));
  CHECK_FALSE(fs::exists(temp));
  writeFileAtomically(target, "complete");
  CHECK(readFile(target, "test") == "complete");
  CHECK(std::distance(fs::directory_iterator(dir), fs::directory_iterator()) == 1);
  fs::remove_all(dir);
}

TEST_CASE("readFile names the missing file") {
  try {
    readFile("/nonexistent/dir/file.xml", "test");
    FAIL("no exception");
  } catch (const Error& e) {
    CHECK(e.file() == "/nonexistent/dir/file.xml");
    CHECK(e.exitCode() == 1);
  }
}
