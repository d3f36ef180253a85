#include "core/temp_dir.h"

#include <fcntl.h>
#include <signal.h>
#include <stdlib.h>
#include <sys/stat.h>
#include <sys/syscall.h>
#include <unistd.h>

#include <atomic>
#include <cerrno>
#include <cstdlib>
#include <cstring>
#include <mutex>

#include "core/error.h"

namespace surrogate {

namespace fs = std::filesystem;

namespace {

// Removes `name` in the folder `parent` (a descriptor, or AT_FDCWD), recursively. System calls
// only: no allocation, no locks, so that the signal handler can call it.
bool removeAt(int parent, const char* name, int depth) {
  if (::unlinkat(parent, name, 0) == 0 || errno == ENOENT) return true;  // a file or a link
  if (errno != EISDIR && errno != EPERM && errno != EACCES) return false;
  if (depth > 64) return false;
  // A folder: full permission for its owner (unlinkat removed it already if it was a link, so
  // this never follows one out of the tree), then its entries, then the folder.
  ::fchmodat(parent, name, S_IRWXU, 0);
  for (int pass = 0; pass < 4; ++pass) {
    if (::unlinkat(parent, name, AT_REMOVEDIR) == 0 || errno == ENOENT) return true;
    if (errno != ENOTEMPTY && errno != EEXIST) return false;
    const int fd = ::openat(parent, name, O_RDONLY | O_DIRECTORY | O_NOFOLLOW | O_CLOEXEC);
    if (fd < 0) return false;
    alignas(8) char buffer[2048];
    for (;;) {
      const long n = ::syscall(SYS_getdents64, fd, buffer, sizeof buffer);
      if (n <= 0) break;
      for (long at = 0; at < n;) {
        // struct linux_dirent64: ino (8), off (8), reclen (2), type (1), name.
        unsigned short length;
        std::memcpy(&length, buffer + at + 16, sizeof length);
        const char* entry = buffer + at + 19;
        if (!(entry[0] == '.' && (entry[1] == 0 || (entry[1] == '.' && entry[2] == 0))))
          removeAt(fd, entry, depth + 1);
        at += length;
      }
    }
    ::close(fd);
  }
  return ::unlinkat(parent, name, AT_REMOVEDIR) == 0;
}

// The live temporary folders, for the signal handler: fixed storage, no allocation.
constexpr int kSlots = 16;
constexpr std::size_t kPathBytes = 4096;
struct Slot {
  std::atomic<int> used{0};
  char path[kPathBytes];
};
Slot slots[kSlots];

struct sigaction previous[3];
constexpr int kSignals[3] = {SIGINT, SIGTERM, SIGHUP};

void onSignal(int signal) {
  for (Slot& s : slots)
    if (s.used.load(std::memory_order_acquire) == 1) removeAt(AT_FDCWD, s.path, 0);
  // End the process as the signal would have (its default action), with its exit status.
  struct sigaction dfl {};
  dfl.sa_handler = SIG_DFL;
  ::sigemptyset(&dfl.sa_mask);
  ::sigaction(signal, &dfl, nullptr);
  ::raise(signal);
}

// Installs onSignal for the signals still at their default action (never replacing a
// program's own handler, nor an "ignore" set by the shell, as for background jobs).
void installHandlers() {
  static std::once_flag once;
  std::call_once(once, [] {
    for (int i = 0; i < 3; ++i) {
      struct sigaction current {};
      if (::sigaction(kSignals[i], nullptr, &current) != 0) continue;
      if (current.sa_handler != SIG_DFL || (current.sa_flags & SA_SIGINFO)) continue;
      struct sigaction ours {};
      ours.sa_handler = onSignal;
      ::sigemptyset(&ours.sa_mask);
      for (int k : kSignals) ::sigaddset(&ours.sa_mask, k);  // one handler at a time
      ::sigaction(kSignals[i], &ours, &previous[i]);
    }
  });
}

int claimSlot(const std::string& path) {
  if (path.size() >= kPathBytes) return -1;
  for (int i = 0; i < kSlots; ++i) {
    int expected = 0;
    if (!slots[i].used.compare_exchange_strong(expected, 2)) continue;  // 2: being filled
    std::memcpy(slots[i].path, path.c_str(), path.size() + 1);
    slots[i].used.store(1, std::memory_order_release);
    return i;
  }
  return -1;  // more than kSlots at once: removed on the normal way out only
}

}  // namespace

bool removeTreeForcibly(const char* path) { return removeAt(AT_FDCWD, path, 0); }

TempDir::TempDir(const std::string& purpose) {
  const char* base = std::getenv("TMPDIR");
  std::string pattern = std::string(base && *base ? base : "/tmp") + "/surrogate-" + purpose + "-XXXXXX";
  installHandlers();
  if (!::mkdtemp(pattern.data()))
    throw Error(ErrorKind::Internal, pattern, purpose,
                std::string("cannot create a temporary folder (") + std::strerror(errno) +
                    "); set TMPDIR to a writable folder with room for the package");
  path_ = fs::absolute(pattern);
  slot_ = claimSlot(path_.string());
}

TempDir::~TempDir() {
  if (slot_ >= 0) slots[slot_].used.store(0, std::memory_order_release);
  // Whatever the work left inside (read-only files or folders), all of it goes.
  if (!removeTreeForcibly(path_.c_str())) {
    std::error_code ec;
    fs::remove_all(path_, ec);
  }
}

}  // namespace surrogate
