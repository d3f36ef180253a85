// The list a batch reads: bounded (no device, FIFO or endless stream fills the memory or
// hangs), one item per capture whatever the spelling, and items passed to the jobs as paths.
#include <sys/stat.h>
#include <unistd.h>

#include <catch2/catch.hpp>
#include <chrono>
#include <filesystem>
#include <fstream>
#include <functional>
#include <sstream>
#include <streambuf>

#include "batch/work_list.h"
#include "core/error.h"

namespace fs = std::filesystem;
using namespace surrogate;
using namespace surrogate::batch;

namespace {

fs::path freshFolder(const std::string& name) {
  const fs::path dir = fs::temp_directory_path() / ("worklist-" + name + "-" + std::to_string(::getpid()));
  fs::remove_all(dir);
  fs::create_directories(dir);
  return dir;
}

// An endless stream of one byte, as `surrogate batch - < /dev/zero` (or `yes`) gives.
class Endless : public std::streambuf {
 public:
  explicit Endless(char c) : block_(1 << 16, c) { setg(block_.data(), block_.data(), block_.data() + block_.size()); }

 protected:
  int_type underflow() override {
    setg(block_.data(), block_.data(), block_.data() + block_.size());
    return traits_type::to_int_type(block_[0]);
  }

 private:
  std::string block_;
};

ErrorKind kindOfRefusal(const std::function<void()>& read) {
  try {
    read();
  } catch (const Error& e) {
    return e.kind();
  }
  FAIL("the list was taken");
  return ErrorKind::Internal;
}

}  // namespace

TEST_CASE("a list that is a device or a FIFO is refused as bad input without being read") {
  const fs::path dir = freshFolder("special");
  const fs::path fifo = dir / "list.fifo";
  REQUIRE(::mkfifo(fifo.c_str(), 0600) == 0);  // no writer: reading it would wait forever
  const auto started = std::chrono::steady_clock::now();
  for (const std::string& list : {std::string("/dev/zero"), fifo.string(), dir.string()}) {
    INFO(list);
    try {
      readWorkList(list);
      FAIL("a list that is not a regular file was taken");
    } catch (const Error& e) {
      CHECK(e.kind() == ErrorKind::Input);
      CHECK(e.file() == list);
      CHECK(e.message().find("is not a regular file") != std::string::npos);
    }
  }
  CHECK(std::chrono::steady_clock::now() - started < std::chrono::seconds(5));
}

TEST_CASE("an endless stream of zeros or of one long line is refused after a bounded read") {
  Endless zeros('\0');
  std::istream zeroStream(&zeros);
  CHECK(kindOfRefusal([&] { readWorkList(zeroStream, "standard input"); }) == ErrorKind::Input);
  // 'a' without a line break: a file larger than any list (kMaxListBytes).
  Endless letters('a');
  std::istream letterStream(&letters);
  try {
    readWorkList(letterStream, "standard input");
    FAIL("an endless list was taken");
  } catch (const Error& e) {
    CHECK(e.kind() == ErrorKind::Input);
    CHECK(e.message().find("is larger than 64 MiB") != std::string::npos);
  }
  std::istringstream longLine("/data/a\n" + std::string(kMaxListLineBytes + 1, 'b') + "\n");
  try {
    readWorkList(longLine, "list.txt");
    FAIL("a line longer than a path was taken");
  } catch (const Error& e) {
    CHECK(e.kind() == ErrorKind::Input);
    CHECK(e.message().find("line 2 is longer than 4096 bytes") != std::string::npos);
  }
}

TEST_CASE("one capture reached by a symbolic link or by its absolute path is one item and the second line is refused") {
  const fs::path dir = freshFolder("spellings");
  fs::create_directories(dir / "cap");
  fs::create_directory_symlink(dir / "cap", dir / "link");
  const fs::path before = fs::current_path();
  fs::current_path(dir);
  for (const std::string& second : {std::string("link"), (dir / "cap").string(), std::string("./cap/."),
                                   std::string("../") + dir.filename().string() + "/cap"}) {
    INFO(second);
    std::istringstream in("cap\n" + second + "\n");
    try {
      readWorkList(in, "list.txt");
      FAIL("one capture was taken twice");
    } catch (const Error& e) {
      CHECK(e.kind() == ErrorKind::Usage);
      CHECK(e.message().find("line 2 (" + second + ") repeats line 1 (cap), both " +
                             fs::canonical(dir / "cap").string()) != std::string::npos);
    }
  }
  std::istringstream two("cap\nlink/../other\n");  // another folder: two items
  CHECK(readWorkList(two, "list.txt").size() == 2);
  fs::current_path(before);
}

TEST_CASE("an item that reads as an option is passed to its job as a path") {
  CHECK(pathArgument("-h") == "./-h");
  CHECK(pathArgument("--help") == "./--help");
  CHECK(pathArgument("-h.zip") == "./-h.zip");
  CHECK(pathArgument("cap") == "cap");
  CHECK(pathArgument("/data/-h") == "/data/-h");
}

TEST_CASE("relative paths of a list file are read from its folder and keep their line as their name") {
  const fs::path dir = freshFolder("relative");
  fs::create_directories(dir / "lists");
  fs::create_directories(dir / "cap");
  std::ofstream(dir / "lists/backlog.txt") << "../cap\n" << (dir / "elsewhere").string() << "\npackages/p.zip\n";
  const std::string list = (dir / "lists/backlog.txt").string();
  const std::vector<WorkItem> items = readWorkList(list);
  REQUIRE(items.size() == 3);
  CHECK(items[0].path == "../cap");  // the ledger's name of it
  CHECK(items[0].where() == (dir / "lists/../cap").string());
  CHECK(items[1].where() == (dir / "elsewhere").string());  // an absolute path is itself
  CHECK(items[2].isPackage);
  CHECK(items[2].where() == (dir / "lists/packages/p.zip").string());
  // The capture by a second spelling, relative to the list, is one item twice.
  std::ofstream(dir / "lists/twice.txt") << "../cap\n" << (dir / "cap").string() << "\n";
  CHECK(kindOfRefusal([&] { readWorkList((dir / "lists/twice.txt").string()); }) == ErrorKind::Usage);
  // The folder is said once, in full.
  CHECK(listFolderNote(list, items) == "Relative paths in " + list + " are read from its folder, " +
                                           (dir / "lists").string() + ".");
  const std::vector<WorkItem> absolute = {items[1]};
  CHECK(listFolderNote(list, absolute).empty());
  // Standard input: the current folder.
  std::istringstream in("cap\n");
  const std::vector<WorkItem> fromInput = readWorkList(in, "standard input");
  CHECK(fromInput[0].where() == "cap");
  CHECK(listFolderNote("-", fromInput) ==
        "Relative paths in the list are read from the current folder, " + fs::current_path().string() + ".");
  fs::remove_all(dir);
}
