#include "capture/lock.h"

#include <fcntl.h>
#include <sys/file.h>
#include <unistd.h>

#include <cerrno>
#include <cstdlib>
#include <cstring>
#include <ctime>

#include "capture/capture.h"
#include "core/error.h"
#include "core/identity.h"

namespace surrogate::capture {

namespace fs = std::filesystem;

namespace {

std::string holderText(const std::string& command) {
  char when[32];
  const std::time_t now = std::time(nullptr);
  std::strftime(when, sizeof when, "%Y-%m-%dT%H:%M:%SZ", std::gmtime(&now));
  return "process " + std::to_string(getpid()) + " on " + hostName() + ", `surrogate " + command +
         "` started " + when + " by " + currentUserName() + "\n";
}

std::string readHolder(int fd) {
  std::string text(512, '\0');
  const ssize_t n = pread(fd, text.data(), text.size(), 0);
  text.resize(n > 0 ? static_cast<std::size_t>(n) : 0);
  while (!text.empty() && (text.back() == '\n' || text.back() == '\0')) text.pop_back();
  return text.empty() ? "another process" : text;
}

}  // namespace

CaptureLock::CaptureLock(const fs::path& capture, const std::string& command) {
  // Nothing is written into a folder that is not a capture (not even the lock). Error codes,
  // not exceptions: a loop of symbolic links is the user's folder, not a bug.
  std::error_code ec;
  const fs::file_status st = fs::status(capture, ec);
  if (!fs::is_directory(st))
    throwInputError(capture.string(), kCaptureCheckStep,
                    ec == std::errc::too_many_symbolic_link_levels
                        ? "is a loop of symbolic links, not a folder; give the capture folder itself"
                    : fs::exists(st) ? "is not a folder; give the capture folder"
                                     : "the capture folder does not exist");
  if (!hasSourceFolder(capture))
    throwInputError(capture.string(), kCaptureCheckStep,
                    "has no original-captures/ (or raw-images/) and no jpeg-exports/ folder; put "
                    "the camera files in original-captures/");
  const fs::path dir = capture / kWorkDir;
  fs::create_directories(dir, ec);
  const fs::path file = dir / "lock";
  fd_ = ::open(file.c_str(), O_RDWR | O_CREAT | O_CLOEXEC | O_NOFOLLOW, 0644);
  if (fd_ < 0)
    throw Error(ErrorKind::Input, file.string(), kCaptureCheckStep,
                std::string("cannot create the capture's lock file (") + std::strerror(errno) +
                    "); Surrogate needs to write in the capture folder");
  if (::flock(fd_, LOCK_EX | LOCK_NB) != 0) refuseHeld(capture);
  const std::string me = holderText(command);
  if (::ftruncate(fd_, 0) == 0) {
    [[maybe_unused]] const ssize_t n = ::pwrite(fd_, me.data(), me.size(), 0);
  }
}

CaptureLock::CaptureLock(const fs::path& capture, const std::string& command, Shared) : shared_(true) {
  (void)command;  // readers leave no holder text: several may hold the lock at once
  std::error_code ec;
  const fs::path dir = capture / kWorkDir;
  fs::create_directories(dir, ec);
  const fs::path file = dir / "lock";
  fd_ = ::open(file.c_str(), O_RDWR | O_CREAT | O_CLOEXEC | O_NOFOLLOW, 0644);
  if (fd_ < 0) fd_ = ::open(file.c_str(), O_RDONLY | O_CLOEXEC | O_NOFOLLOW);
  if (fd_ < 0) return;  // a read-only capture: nothing can write in it either
  if (::flock(fd_, LOCK_SH | LOCK_NB) != 0) refuseHeld(capture);
}

void CaptureLock::refuseHeld(const fs::path& capture) {
  const std::string holder = readHolder(fd_);
  ::close(fd_);
  fd_ = -1;
  throw Error(ErrorKind::Input, capture.string(), kCaptureHeldStep,
              "another Surrogate command is working on this capture (" + holder +
                  "); wait for it to finish, then run this command again");
}

std::optional<std::string> captureHolder(const fs::path& capture) {
  const int fd = ::open((capture / kWorkDir / "lock").c_str(), O_RDONLY | O_CLOEXEC | O_NOFOLLOW);
  if (fd < 0) return std::nullopt;  // never locked, or unreadable: no holder to name
  std::optional<std::string> holder;
  if (::flock(fd, LOCK_SH | LOCK_NB) != 0) holder = readHolder(fd);
  ::close(fd);  // releases the shared lock, if taken
  return holder;
}

CaptureLock::~CaptureLock() {
  if (fd_ >= 0) {
    if (!shared_) {
      [[maybe_unused]] const int r = ::ftruncate(fd_, 0);
    }
    ::close(fd_);  // releases the lock
  }
}

}  // namespace surrogate::capture
