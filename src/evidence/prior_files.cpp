#include "evidence/prior_files.h"

#include <dirent.h>
#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <cstring>
#include <vector>

#include "capture/capture.h"
#include "core/atomic_file.h"
#include "core/digest.h"
#include "core/error.h"
#include "core/file_names.h"

namespace surrogate::evidence {

namespace fs = std::filesystem;

namespace {

constexpr const char* kStep = "audit evidence";
constexpr std::size_t kBufferBytes = 1 << 20;
// PRIOR's carrier, read whole to tell Surrogate's results from prior work: carriers of 100,000
// files are tens of megabytes.
constexpr std::uintmax_t kMaxSmallFileBytes = 256u << 20;

// A file descriptor closed when it goes out of scope.
class Fd {
 public:
  explicit Fd(int fd) : fd_(fd) {}
  ~Fd() {
    if (fd_ >= 0) ::close(fd_);
  }
  Fd(const Fd&) = delete;
  Fd& operator=(const Fd&) = delete;
  int get() const { return fd_; }
  int release() {
    const int fd = fd_;
    fd_ = -1;
    return fd;
  }

 private:
  int fd_;
};

std::string shown(const std::string& relative) { return shownName(relative); }

// Opens for reading with O_NOATIME, or without it where the system refuses it (a file of
// another user, for whom the flag is not allowed).
int openReading(const fs::path& path, int flags) {
  int fd = ::open(path.c_str(), flags | O_RDONLY | O_CLOEXEC | O_NOFOLLOW | O_NOATIME);
  if (fd < 0 && errno == EPERM) fd = ::open(path.c_str(), flags | O_RDONLY | O_CLOEXEC | O_NOFOLLOW);
  return fd;
}

[[noreturn]] void unreadable(const std::string& relative, int error) {
  if (error == ELOOP)
    throwInputError(shown(relative), kStep,
                    "is a symbolic link; an audit copies files, and a link's target can change or lie "
                    "outside the folder audited. Copy the folder with the linked files in place of the links, "
                    "and audit the copy");
  throwInputError(shown(relative), kStep, std::string("cannot be read (") + std::strerror(error) +
                                             "); check your permissions");
}

bool skipped(const std::string& relative, const std::string& name, bool isDirectory) {
  if (capture::isSystemFile(name)) return true;
  const bool top = relative.find('/') == std::string::npos;
  if (top && isDirectory && (name == capture::kWorkDir || name == capture::kSupersededDir)) return true;
  const auto inOutputFolder = [&](const char* dir) { return relative.rfind(std::string(dir) + "/", 0) == 0; };
  return !isDirectory && capture::isInterruptedWrite(name) &&
         (inOutputFolder(capture::kAssemblyDir) || inOutputFolder(capture::kFinishedDir));
}

void walk(const fs::path& dir, const std::string& relativeDir, std::vector<std::string>& out) {
  Fd fd(openReading(dir, O_DIRECTORY));
  if (fd.get() < 0) unreadable(relativeDir.empty() ? dir.string() : relativeDir, errno);
  DIR* stream = ::fdopendir(fd.get());
  if (!stream) unreadable(relativeDir, errno);
  const int dirFd = fd.release();  // closedir closes it
  struct Closer {
    DIR* d;
    ~Closer() { ::closedir(d); }
  } closer{stream};
  std::vector<std::pair<std::string, bool>> entries;  // name, is a folder
  errno = 0;
  while (const dirent* e = ::readdir(stream)) {
    const std::string name = e->d_name;
    if (name == "." || name == "..") continue;
    const std::string relative = relativeDir.empty() ? name : relativeDir + "/" + name;
    struct stat st {};
    if (::fstatat(dirFd, e->d_name, &st, AT_SYMLINK_NOFOLLOW) != 0) unreadable(relative, errno);
    if (S_ISLNK(st.st_mode)) unreadable(relative, ELOOP);
    if (!S_ISDIR(st.st_mode) && !S_ISREG(st.st_mode))
      throwInputError(shown(relative), kStep,
                      "is not a regular file (a device, pipe or socket); an audit copies only files");
    if (!skipped(relative, name, S_ISDIR(st.st_mode))) entries.emplace_back(name, S_ISDIR(st.st_mode));
    errno = 0;
  }
  if (errno != 0) unreadable(relativeDir, errno);
  for (const auto& [name, isDirectory] : entries) {
    const std::string relative = relativeDir.empty() ? name : relativeDir + "/" + name;
    if (isDirectory) walk(dir / name, relative, out);
    else out.push_back(relative);
  }
}

std::uint64_t fileSize(int fd, const std::string& relative) {
  struct stat st {};
  if (::fstat(fd, &st) != 0) unreadable(relative, errno);
  if (!S_ISREG(st.st_mode)) throwInputError(shown(relative), kStep, "is no longer a regular file");
  return static_cast<std::uint64_t>(st.st_size);
}

void writeAll(int fd, const char* data, std::size_t size, const fs::path& target) {
  while (size > 0) {
    const ssize_t n = ::write(fd, data, size);
    if (n < 0) {
      if (errno == EINTR) continue;
      throw writeError(target, kStep, errno);
    }
    data += n;
    size -= static_cast<std::size_t>(n);
  }
}

// Reads `fd` to its end, feeding `sink`; returns the byte count.
template <typename Sink>
std::uint64_t readAll(int fd, const std::string& relative, Sink&& sink) {
  std::vector<char> buffer(kBufferBytes);
  std::uint64_t total = 0;
  for (;;) {
    const ssize_t n = ::read(fd, buffer.data(), buffer.size());
    if (n < 0) {
      if (errno == EINTR) continue;
      unreadable(relative, errno);
    }
    if (n == 0) return total;
    sink(buffer.data(), static_cast<std::size_t>(n));
    total += static_cast<std::uint64_t>(n);
  }
}

void requireSize(std::uint64_t read, std::uint64_t expected, const std::string& relative) {
  if (read != expected)
    throwInputError(shown(relative), kStep,
                    "changed while it was read (" + std::to_string(expected) + " bytes at the start, " +
                        std::to_string(read) + " read): audit a folder nothing is writing to");
}

}  // namespace

std::vector<std::string> listFiles(const fs::path& root) {
  std::vector<std::string> out;
  walk(root, "", out);
  std::sort(out.begin(), out.end());
  return out;
}

bool holdsFile(const fs::path& folder) {
  Fd fd(openReading(folder, O_DIRECTORY));
  if (fd.get() < 0) return false;
  DIR* stream = ::fdopendir(fd.get());
  if (!stream) return false;
  const int dirFd = fd.release();  // closedir closes it
  bool found = false;
  while (const dirent* e = ::readdir(stream)) {
    struct stat st {};
    if (::fstatat(dirFd, e->d_name, &st, AT_SYMLINK_NOFOLLOW) == 0 && S_ISREG(st.st_mode) &&
        !capture::isSystemFile(e->d_name)) {
      found = true;
      break;
    }
  }
  ::closedir(stream);
  return found;
}

std::string readSmallFile(const fs::path& file) {
  Fd fd(openReading(file, 0));
  if (fd.get() < 0) unreadable(file.string(), errno);
  const std::uint64_t size = fileSize(fd.get(), file.string());
  if (size > kMaxSmallFileBytes)
    throwInputError(file.string(), kStep, "is larger than a carrier Surrogate reads (" +
                                              std::to_string(kMaxSmallFileBytes >> 20) + " MB)");
  std::string out;
  out.reserve(static_cast<std::size_t>(size));
  readAll(fd.get(), file.string(), [&](const char* data, std::size_t n) { out.append(data, n); });
  return out;
}

carrier::AuditedSource::Item hashFile(const fs::path& root, const std::string& relative) {
  Fd fd(openReading(root / fs::u8path(relative), 0));
  if (fd.get() < 0) unreadable(relative, errno);
  const std::uint64_t size = fileSize(fd.get(), relative);
  MultiDigest digest({DigestAlgorithm::Sha256});
  requireSize(readAll(fd.get(), relative, [&](const char* data, std::size_t n) { digest.update(data, n); }), size,
              relative);
  return {relative, relative, size, digest.hex(DigestAlgorithm::Sha256)};
}

carrier::AuditedSource::Item copyFile(const fs::path& root, const std::string& relative, const fs::path& destination) {
  Fd in(openReading(root / fs::u8path(relative), 0));
  if (in.get() < 0) unreadable(relative, errno);
  struct stat st {};
  if (::fstat(in.get(), &st) != 0) unreadable(relative, errno);
  const std::uint64_t size = fileSize(in.get(), relative);

  const fs::path target = destination / fs::u8path(relative);
  std::error_code ec;
  fs::create_directories(target.parent_path(), ec);
  if (ec) throw writeError(target.parent_path(), kStep, ec.value());
  Fd out(::open(target.c_str(), O_WRONLY | O_CREAT | O_EXCL | O_NOFOLLOW | O_CLOEXEC, 0644));
  if (out.get() < 0) throw writeError(target, kStep, errno);
  MultiDigest digest({DigestAlgorithm::Sha256});
  const std::uint64_t copied = readAll(in.get(), relative, [&](const char* data, std::size_t n) {
    digest.update(data, n);
    writeAll(out.get(), data, n, target);
  });
  requireSize(copied, size, relative);
  if (::fdatasync(out.get()) != 0) throw writeError(target, kStep, errno);
  // The copy keeps the original's modification time: an auditor sees the dates PRIOR has.
  const timespec times[2] = {st.st_atim, st.st_mtim};
  ::futimens(out.get(), times);
  return {relative, relative, size, digest.hex(DigestAlgorithm::Sha256)};
}

}  // namespace surrogate::evidence
