#include <catch2/catch.hpp>

#include <sys/resource.h>

#include <csignal>
#include <cerrno>
#include <filesystem>
#include <fstream>
#include <string>

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

namespace {
// Bytes in an order of their own (no stride or buffer size repeats them), several MB so that
// writeback starts several times while they are written.
std::string patterned(std::size_t n) {
  std::string s(n, '\0');
  for (std::size_t i = 0; i < n; ++i) s[i] = static_cast<char>((i * 2654435761u) >> 13);
  return s;
}
}  // namespace

TEST_CASE("writeTemporary's stream gives the file exactly its bytes, small writes and large") {
  const fs::path dir = fs::temp_directory_path() / "surrogate-test-atomic-stream";
  fs::remove_all(dir);
  fs::create_directories(dir);
  const std::string big = patterned(5 * 1024 * 1024 + 12345);
  std::string expected;
  AtomicFile file(dir / "model.bin");
  writeTemporary(file, "test", [&](std::ostream& out) {
    // A header, then rows of a few KB (as a PTM), single bytes, then one block of MB (as an RTI).
    out << "HEADER\n";
    expected += "HEADER\n";
    for (std::size_t at = 0; at + 7200 <= 3 * 1024 * 1024; at += 7200) {
      out.write(big.data() + at, 7200);
      expected.append(big, at, 7200);
    }
    out.put('x');
    expected += 'x';
    out.write(big.data(), static_cast<std::streamsize>(big.size()));
    expected += big;
  });
  CHECK_FALSE(fs::exists(dir / "model.bin"));  // not in place before commit()
  file.commit();
  CHECK(readFile(dir / "model.bin", "test") == expected);
  CHECK(std::distance(fs::directory_iterator(dir), fs::directory_iterator()) == 1);
  fs::remove_all(dir);
}

TEST_CASE("writeTemporary's stream names the final file when the disk fills") {
  const fs::path dir = fs::temp_directory_path() / "surrogate-test-atomic-full";
  fs::remove_all(dir);
  fs::create_directories(dir);
  const std::string big = patterned(4 * 1024 * 1024);
  // A file-size limit stands in for a full disk: past it, write(2) fails (EFBIG).
  struct rlimit old {};
  ::getrlimit(RLIMIT_FSIZE, &old);
  const auto oldHandler = std::signal(SIGXFSZ, SIG_IGN);
  struct rlimit small = old;
  small.rlim_cur = 3 * 1024 * 1024 + 100;  // past a writeback stride, before the end
  ::setrlimit(RLIMIT_FSIZE, &small);
  bool threw = false;
  try {
    AtomicFile file(dir / "model.ptm");
    writeTemporary(file, "write PTM", [&](std::ostream& out) {
      out.write(big.data(), 1000);  // a small write first: the buffered path fails too
      out.write(big.data(), static_cast<std::streamsize>(big.size()));
    });
    file.commit();
  } catch (const Error& e) {
    threw = true;
    CHECK(e.file() == (dir / "model.ptm").string());
    CHECK(e.exitCode() == 1);
    CHECK(e.message().find("ulimit -f") != std::string::npos);
  }
  ::setrlimit(RLIMIT_FSIZE, &old);
  std::signal(SIGXFSZ, oldHandler);
  CHECK(threw);
  CHECK(fs::is_empty(dir));  // neither the final name nor the temporary
  fs::remove_all(dir);
}

TEST_CASE("writeTemporary names the final file when its temporary cannot be made") {
  AtomicFile file("/nonexistent/dir/model.rti");
  try {
    writeTemporary(file, "write RTI", [](std::ostream& out) { out << "bytes"; });
    FAIL("no exception");
  } catch (const Error& e) {
    CHECK(e.file() == "/nonexistent/dir/model.rti");
    CHECK(e.exitCode() == 1);
  }
}
