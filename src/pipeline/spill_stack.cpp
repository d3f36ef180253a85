#include "pipeline/spill_stack.h"

#include <fcntl.h>
#include <sys/statvfs.h>
#include <unistd.h>

#include <cerrno>
#include <cstdlib>
#include <cstring>
#include <string>

#include "core/error.h"

namespace surrogate::pipeline {

namespace fs = std::filesystem;

fs::path spillDirectory(const fs::path& requested) {
  if (!requested.empty()) return requested;
  const char* tmp = std::getenv("TMPDIR");
  return tmp && *tmp ? fs::path(tmp) : fs::path("/tmp");
}

std::optional<std::uint64_t> spillSpaceAvailable(const fs::path& directory) {
  struct statvfs st {};
  if (::statvfs(spillDirectory(directory).c_str(), &st) != 0) return std::nullopt;
  return static_cast<std::uint64_t>(st.f_bavail) * st.f_frsize;
}

std::uint64_t spillBytes(int count, int width, int height, int channels) {
  return static_cast<std::uint64_t>(count) * static_cast<std::uint64_t>(width) *
         static_cast<std::uint64_t>(height) * static_cast<std::uint64_t>(channels) * sizeof(std::uint16_t);
}

namespace {

[[noreturn]] void spillFailure(const fs::path& dir, const char* what) {
  throw Error(ErrorKind::Internal, dir.string(), "image stack",
              std::string("could not ") + what + " the temporary pixel file (" +
                  std::strerror(errno) + "); check free space in that folder or set TMPDIR");
}
}  // namespace

SpillStack::SpillStack(int count, int width, int height, int channels, Transfer transfer,
                       const fs::path& directory)
    : count_(count), width_(width), height_(height), channels_(channels), transfer_(transfer) {
  const fs::path dir = spillDirectory(directory);
  fd_ = ::open(dir.c_str(), O_TMPFILE | O_RDWR | O_CLOEXEC, 0600);
  if (fd_ < 0) {
    // Filesystems without O_TMPFILE: create and unlink at once.
    std::string pattern = (dir / "surrogate-stack-XXXXXX").string();
    fd_ = ::mkstemp(pattern.data());
    if (fd_ < 0) spillFailure(dir, "create");
    ::unlink(pattern.c_str());
  }
}

SpillStack::~SpillStack() {
  if (fd_ >= 0) ::close(fd_);
}

std::uint64_t SpillStack::imageBytes() const {
  return static_cast<std::uint64_t>(width_) * height_ * channels_ * sizeof(std::uint16_t);
}

void SpillStack::write(int index, const Image& image) {
  if (index < 0 || index >= count_ || image.width != width_ || image.height != height_ ||
      image.channels != channels_) {
    throw Error(ErrorKind::Internal, "", "image stack", "image does not fit the stack");
  }
  const char* data = reinterpret_cast<const char*>(image.pixels.data());
  std::uint64_t left = imageBytes();
  off_t offset = static_cast<off_t>(imageBytes() * index);
  while (left > 0) {
    const ssize_t n = ::pwrite(fd_, data, left, offset);
    if (n <= 0) {
      if (n < 0 && errno == EINTR) continue;
      spillFailure(spillDirectory({}), "write");
    }
    data += n;
    left -= static_cast<std::uint64_t>(n);
    offset += n;
  }
}

void SpillStack::readRows(int index, int y0, int y1, std::uint16_t* out) const {
  if (index < 0 || index >= count_ || y0 < 0 || y1 > height_ || y0 > y1)
    throw Error(ErrorKind::Internal, "", "image stack", "row range outside the stack");
  const std::uint64_t rowBytes = static_cast<std::uint64_t>(width_) * channels_ * 2;
  char* dst = reinterpret_cast<char*>(out);
  std::uint64_t left = rowBytes * (y1 - y0);
  off_t offset = static_cast<off_t>(imageBytes() * index + rowBytes * y0);
  while (left > 0) {
    const ssize_t n = ::pread(fd_, dst, left, offset);
    if (n <= 0) {
      if (n < 0 && errno == EINTR) continue;
      spillFailure(spillDirectory({}), "read");
    }
    dst += n;
    left -= static_cast<std::uint64_t>(n);
    offset += n;
  }
}

Image SpillStack::read(int index) const {
  Image im(width_, height_, channels_);
  im.transfer = transfer_;
  readRows(index, 0, height_, im.pixels.data());
  return im;
}

}  // namespace surrogate::pipeline
