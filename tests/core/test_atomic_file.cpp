#include <catch2/catch.hpp>

#include <cerrno>
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

TEST_CASE("commitWithoutReplacing never replaces what appeared at the final name meanwhile") {
  const fs::path dir = fs::temp_directory_path() / "surrogate-test-atomic-noreplace";
  fs::remove_all(dir);
  fs::create_directories(dir);
  const fs::path target = dir / "pkg.zip";
  {
    AtomicFile mine(target);
    writeTemporary(mine, "mine");
    writeFileAtomically(target, "theirs");  // another process finished first
    try {
      mine.commitWithoutReplacing();
      FAIL("no exception");
    } catch (const Error& e) {
      CHECK(e.exitCode() == 1);
      CHECK(e.file() == target.string());
    }
  }
  CHECK(readFile(target, "test") == "theirs");
  CHECK(std::distance(fs::directory_iterator(dir), fs::directory_iterator()) == 1);  // no temporary left
  {
    AtomicFile fresh(dir / "new.zip");
    writeTemporary(fresh, "new");
    fresh.commitWithoutReplacing();
  }
  CHECK(readFile(dir / "new.zip", "test") == "new");
  fs::remove_all(dir);
}

TEST_CASE("commitWithoutReplacing fills an empty folder but never a full one") {
  const fs::path dir = fs::temp_directory_path() / "surrogate-test-atomic-folder";
  fs::remove_all(dir);
  fs::create_directories(dir / "empty");
  fs::create_directories(dir / "full");
  std::ofstream(dir / "full" / "kept.txt") << "kept";
  for (const char* name : {"empty", "full"}) {
    AtomicFile bag(dir / name);
    fs::create_directories(bag.tempPath());
    std::ofstream(bag.tempPath() / "bagit.txt") << "BagIt-Version: 1.0\n";
    if (std::string(name) == "empty") {
      bag.commitWithoutReplacing();
      CHECK(fs::exists(dir / name / "bagit.txt"));
    } else {
      CHECK_THROWS_AS(bag.commitWithoutReplacing(), Error);
    }
  }
  CHECK(readFile(dir / "full" / "kept.txt", "test") == "kept");
  CHECK_FALSE(fs::exists(dir / "full" / "bagit.txt"));
  fs::remove_all(dir);
}

TEST_CASE("writeError says what the environment refused, as exit 1") {
  const Error full = writeError("/data/pkg.zip", "packing", ENOSPC);
  CHECK(full.exitCode() == 1);
  CHECK(full.message().find("disk is full") != std::string::npos);
  CHECK(writeError("/data/pkg.zip", "packing", EFBIG).message().find("ulimit -f") != std::string::npos);
  CHECK(writeError("/data/pkg.zip", "packing", EROFS).message().find("read-only") != std::string::npos);
  CHECK(writeError("/data/pkg.zip", "packing", EACCES).message().find("permission denied") != std::string::npos);
}
