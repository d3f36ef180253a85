// The main of every test program: Catch2's runner inside a scratch folder of its own.
//
// Tests make folders with fs::temp_directory_path() and run surrogate, which also writes there.
// Pointing TMPDIR at one folder per test process and removing it when the process ends keeps a
// test run from leaving gigabytes behind (hundreds of runs once filled a CI disk). Set
// SURROGATE_KEEP_TEST_DIRS=1 to keep the folder for a look after a failure; its path is printed.
#define CATCH_CONFIG_RUNNER
#include <catch2/catch.hpp>

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <cstdlib>
#include <filesystem>
#include <iostream>
#include <string>
#include <system_error>

namespace fs = std::filesystem;

namespace {

// Some tests leave folders read-only on purpose (an unwritable capture); give them back write
// permission so that they can be removed.
void makeWritable(const fs::path& root) {
  std::error_code ec;
  fs::permissions(root, fs::perms::owner_all, fs::perm_options::add, ec);
  for (fs::recursive_directory_iterator it(root, fs::directory_options::skip_permission_denied, ec), end;
       !ec && it != end; it.increment(ec)) {
    std::error_code ignored;
    if (it->is_directory(ignored) && !it->is_symlink(ignored))
      fs::permissions(it->path(), fs::perms::owner_all, fs::perm_options::add, ignored);
  }
}

void removeScratch(const fs::path& dir) {
  std::error_code ec;
  fs::remove_all(dir, ec);
  if (ec) {
    makeWritable(dir);
    fs::remove_all(dir, ec);
  }
  if (ec) std::cerr << "could not remove the test scratch folder " << dir << ": " << ec.message() << "\n";
}

// CI runs the suite with standard input closed. A program started without descriptor 0 gives
// that number to the next file or socket it opens, and a daemon a test starts (slurmd) then
// failed every job it launched: the test program, and so everything it starts, gets /dev/null
// for a standard stream that is closed.
void openClosedStandardStreams() {
  for (int fd = 0; fd <= 2; ++fd)
    if (::fcntl(fd, F_GETFD) == -1 && errno == EBADF) ::open("/dev/null", fd == 0 ? O_RDONLY : O_WRONLY);
}

}  // namespace

int main(int argc, char* argv[]) {
  openClosedStandardStreams();  // lowest free descriptor first: each lands on its own number
  std::error_code ec;
  const fs::path scratch =
      fs::temp_directory_path(ec) / ("surrogate-tests-" + std::to_string(::getpid()));
  fs::remove_all(scratch, ec);
  const bool haveScratch = !ec && fs::create_directories(scratch, ec) && !ec;
  if (haveScratch) ::setenv("TMPDIR", scratch.c_str(), 1);

  const int result = Catch::Session().run(argc, argv);

  if (haveScratch) {
    if (std::getenv("SURROGATE_KEEP_TEST_DIRS"))
      std::cerr << "test files kept in " << scratch << "\n";
    else
      removeScratch(scratch);
  }
  return result;
}
