// One process at a time on a capture: an advisory lock (flock) on CAPTURE/.surrogate/lock.
//
// `run`, `lights` and `pack` hold it for their whole duration, so two of them never interleave
// their writes (a carrier whose hashes match no file on disk, a pack that re-runs the pipeline
// under a user's run). The lock file holds who holds it (process id, host, command, user,
// start time) for the message the second process prints. The kernel releases the lock when
// the holder exits, however it exits (kill -9 included): no stale lock to clean up by hand.
//
//   CaptureLock lock(capturePath, "run");   // throws Error(Input) naming the holder if held
#pragma once

#include <filesystem>
#include <optional>
#include <string>

#include "capture/capture.h"

namespace surrogate::capture {

// The step an Error names when another process holds the capture, and only then: a batch waits
// for the capture and comes back, the review page answers "busy". The lock's other refusals (no
// such folder, not a capture, no lock file can be made) name kCaptureCheckStep (capture.h):
// they are not waited out.
inline constexpr const char* kCaptureHeldStep = "lock";

class CaptureLock {
 public:
  // Takes the lock, creating CAPTURE/.surrogate/ if needed. Throws Error(Input) naming the
  // holder when another process has it, and for a folder that is not a capture (no folder of
  // originals or exports), so that nothing is written into such a folder.
  CaptureLock(const std::filesystem::path& capture, const std::string& command);
  // A reader's lock (`report` of a capture): shared with other readers, refused while a
  // command that writes holds the capture (and keeps such a command out meanwhile). A capture
  // in which no lock file can be made (read-only) is read without one: nothing writes there.
  struct Shared {};
  CaptureLock(const std::filesystem::path& capture, const std::string& command, Shared);
  ~CaptureLock();
  CaptureLock(const CaptureLock&) = delete;
  CaptureLock& operator=(const CaptureLock&) = delete;

 private:
  // Closes the lock file and throws Error(Input) naming who holds the capture.
  [[noreturn]] void refuseHeld(const std::filesystem::path& capture);

  int fd_ = -1;
  bool shared_ = false;
};

// Who holds the capture for writing (the holder's text: process id, host, command, user, start
// time), or nothing when no command that writes holds it. Takes nothing and makes nothing: for
// `info`, which reads only. (A shared lock is tried for an instant, as a reader's.)
std::optional<std::string> captureHolder(const std::filesystem::path& capture);

}  // namespace surrogate::capture
