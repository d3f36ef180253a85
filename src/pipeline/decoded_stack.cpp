#include "pipeline/decoded_stack.h"

#include <fcntl.h>
#include <sys/statvfs.h>
#include <unistd.h>

#include <cerrno>
#include <cstdlib>
#include <cstring>
#include <string>

#include "core/error.h"
#include "core/resident.h"

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

namespace {

[[noreturn]] void spillFailure(const fs::path& dir, const char* what) {
  throw Error(ErrorKind::Internal, dir.string(), "image stack",
              std::string("could not ") + what + " the temporary pixel file (" +
                  std::strerror(errno) + "); check free space in that folder or set TMPDIR");
}

[[noreturn]] void misuse(const char* what) { throw Error(ErrorKind::Internal, "", "image stack", what); }

int temporaryFile(const fs::path& dir) {
  int fd = ::open(dir.c_str(), O_TMPFILE | O_RDWR | O_CLOEXEC, 0600);
  if (fd >= 0) return fd;
  // Filesystems without O_TMPFILE: create and unlink at once.
  std::string pattern = (dir / "surrogate-stack-XXXXXX").string();
  fd = ::mkstemp(pattern.data());
  if (fd < 0) spillFailure(dir, "create");
  ::unlink(pattern.c_str());
  return fd;
}

// pwrite/pread until all `bytes` moved (they may move less at once, or be interrupted).
template <typename Call, typename Pointer>
void transferAll(Call call, int fd, Pointer data, std::uint64_t bytes, off_t offset, const char* what) {
  while (bytes > 0) {
    const ssize_t n = call(fd, data, bytes, offset);
    if (n <= 0) {
      if (n < 0 && errno == EINTR) continue;
      spillFailure(spillDirectory({}), what);
    }
    data += n;
    bytes -= static_cast<std::uint64_t>(n);
    offset += n;
  }
}

}  // namespace

std::uint64_t DecodedStack::bytesFor(int count, const Format& f) {
  return static_cast<std::uint64_t>(count) * static_cast<std::uint64_t>(f.width) *
         static_cast<std::uint64_t>(f.height) * static_cast<std::uint64_t>(f.channels) *
         static_cast<std::uint64_t>(f.bytesPerSample);
}

DecodedStack::DecodedStack(int count, Format format, Placement placement, const fs::path& directory)
    : count_(count), format_(format), placement_(placement) {
  if (count < 0 || format.width <= 0 || format.height <= 0 || (format.channels != 1 && format.channels != 3) ||
      (format.bytesPerSample != 1 && format.bytesPerSample != 2))
    misuse("a stack of images of no size or an unknown layout");
  if (placement == Placement::TemporaryFile) {
    fd_ = temporaryFile(spillDirectory(directory));
  } else {
    // A mapping of its own (page-aligned, so 16-bit samples are aligned too), whatever malloc's
    // policy (core/resident.h: reuseFreedMemory), given back when the stack goes.
    // Not zeroed here: each slot's pages are backed by the thread that fills it, just before
    // (core/resident.h).
    block_ = MappedBlock(static_cast<std::size_t>(bytesFor(count, format)));
  }
  stored_.assign(static_cast<std::size_t>(count), 0);
}

DecodedStack::~DecodedStack() {
  if (fd_ >= 0) ::close(fd_);
}

std::uint64_t DecodedStack::rowBytes() const {
  return static_cast<std::uint64_t>(format_.width) * format_.channels * format_.bytesPerSample;
}

std::uint64_t DecodedStack::imageBytes() const { return rowBytes() * format_.height; }

void DecodedStack::checkIndex(int index) const {
  if (index < 0 || index >= count_) misuse("image index outside the stack");
}

std::uint8_t* DecodedStack::slot(int index) {
  checkIndex(index);
  if (placement_ != Placement::Memory) return nullptr;
  return block_.data() + imageBytes() * static_cast<std::uint64_t>(index);
}

void DecodedStack::markStored(int index) {
  checkIndex(index);
  if (placement_ != Placement::Memory) misuse("an image marked stored in a stack kept in a file");
  stored_[static_cast<std::size_t>(index)] = 1;
}

void DecodedStack::storeBytes(int index, const void* samples) {
  if (placement_ == Placement::Memory) {
    makeResidentAdvised(slot(index), static_cast<std::size_t>(imageBytes()));
    std::memcpy(slot(index), samples, static_cast<std::size_t>(imageBytes()));
  } else {
    transferAll(::pwrite, fd_, static_cast<const char*>(samples), imageBytes(),
                static_cast<off_t>(imageBytes() * index), "write");
  }
  stored_[static_cast<std::size_t>(index)] = 1;
}

void DecodedStack::store(int index, const std::vector<std::uint8_t>& samples) {
  if (format_.bytesPerSample != 1 || index < 0 || index >= count_ || samples.size() != imageBytes())
    misuse("8-bit image does not fit the stack");
  storeBytes(index, samples.data());
}

void DecodedStack::store(int index, const std::vector<std::uint16_t>& samples) {
  if (format_.bytesPerSample != 2 || index < 0 || index >= count_ || samples.size() * 2 != imageBytes())
    misuse("16-bit image does not fit the stack");
  storeBytes(index, samples.data());
}

void DecodedStack::checkRows(int index, int y0, int y1) const {
  if (index < 0 || index >= count_ || y0 < 0 || y1 > format_.height || y0 > y1) misuse("row range outside the stack");
  if (!stored_[static_cast<std::size_t>(index)]) misuse("image read before it was stored");
}

const std::uint8_t* DecodedStack::storedImage(int index) const {
  return block_.data() + imageBytes() * static_cast<std::uint64_t>(index);
}

void DecodedStack::readSamples(int index, int y0, int y1, void* out) const {
  checkRows(index, y0, y1);
  const std::uint64_t offset = rowBytes() * y0, bytes = rowBytes() * (y1 - y0);
  if (placement_ == Placement::TemporaryFile) {
    transferAll(::pread, fd_, static_cast<char*>(out), bytes, static_cast<off_t>(imageBytes() * index + offset),
                "read");
    return;
  }
  std::memcpy(out, storedImage(index) + offset, bytes);
}

const std::uint8_t* DecodedStack::heldSamples(int index, int y0, int y1) const {
  checkRows(index, y0, y1);
  if (placement_ != Placement::Memory) return nullptr;
  return storedImage(index) + rowBytes() * y0;
}

const std::uint8_t* DecodedStack::heldByteRow(int index, int y) const {
  return format_.bytesPerSample == 1 ? heldSamples(index, y, y + 1) : nullptr;
}

void DecodedStack::readRows(int index, int y0, int y1, std::uint16_t* out) const {
  if (format_.bytesPerSample == 2) {
    readSamples(index, y0, y1, out);
    return;
  }
  checkRows(index, y0, y1);
  const std::size_t samples = static_cast<std::size_t>(rowBytes()) * (y1 - y0);
  if (placement_ == Placement::Memory) {
    widenSamples(storedImage(index) + rowBytes() * y0, samples, out);
    return;
  }
  std::vector<std::uint8_t> bytes(samples);
  readSamples(index, y0, y1, bytes.data());
  widenSamples(bytes.data(), samples, out);
}

}  // namespace surrogate::pipeline
