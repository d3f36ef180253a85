#include "publish/layout_files.h"

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>

#include "core/error.h"

namespace surrogate::publish {

namespace fs = std::filesystem;

namespace {
const char* const kLinkRefused =
    "is a symbolic link; a web layout's files are read as they are, never through a link (its "
    "target could be any file): replace the link by a copy of the file it points to";

class Descriptor {
 public:
  explicit Descriptor(int fd) : fd_(fd) {}
  ~Descriptor() {
    if (fd_ >= 0) ::close(fd_);
  }
  Descriptor(const Descriptor&) = delete;
  Descriptor& operator=(const Descriptor&) = delete;
  int get() const { return fd_; }

 private:
  int fd_;
};
}  // namespace

bool somethingAt(const fs::path& path) {
  std::error_code ec;
  return fs::exists(fs::symlink_status(path, ec));
}

void refuseLinkedFolder(const fs::path& folder, const std::string& step) {
  std::error_code ec;
  if (fs::is_symlink(fs::symlink_status(folder, ec))) throwInputError(folder.string(), step, kLinkRefused);
}

std::string readLayoutFile(const fs::path& file, std::uintmax_t maxBytes, const std::string& step) {
  // O_NONBLOCK: a FIFO put in place of a plane must not hang the reader; fstat refuses it.
  const Descriptor fd(::open(file.c_str(), O_RDONLY | O_NOFOLLOW | O_NONBLOCK | O_CLOEXEC));
  if (fd.get() < 0) {
    const int error = errno;
    std::error_code ec;
    if (error == ELOOP || fs::is_symlink(fs::symlink_status(file, ec))) throwInputError(file.string(), step, kLinkRefused);
    throwInputError(file.string(), step, std::string("cannot be opened: ") + std::strerror(error));
  }
  struct stat st {};
  if (::fstat(fd.get(), &st) != 0 || !S_ISREG(st.st_mode))
    throwInputError(file.string(), step, "is not a regular file (a folder, device or pipe); a web layout holds files");
  const auto size = static_cast<std::uintmax_t>(st.st_size);
  if (size > maxBytes)
    throwInputError(file.string(), step,
                    "holds " + std::to_string(size) + " bytes, more than the " + std::to_string(maxBytes) +
                        " such a file of this layout can have: it does not belong to the layout");
  std::string out(static_cast<std::size_t>(size), '\0');
  std::size_t done = 0;
  while (done < out.size()) {
    const ssize_t n = ::read(fd.get(), out.data() + done, out.size() - done);
    if (n < 0 && errno == EINTR) continue;
    if (n < 0) throwInputError(file.string(), step, std::string("reading it failed: ") + std::strerror(errno));
    if (n == 0) break;
    done += static_cast<std::size_t>(n);
  }
  out.resize(done);  // a file that shrank meanwhile is read as it is; the decoders check the rest
  return out;
}

}  // namespace surrogate::publish
