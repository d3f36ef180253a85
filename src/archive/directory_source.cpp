// A bag directory as the package reader's source of entries: walked without following links,
// in sorted order, every file opened with O_NOFOLLOW and checked to be the regular file it was
// listed as. What the entries may be is checked for every container alike (entry_checks.cpp).
#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <cstring>
#include <vector>

#include "archive/entry_checks.h"
#include "archive/package_source.h"
#include "core/error.h"

namespace fs = std::filesystem;

namespace surrogate::archive {

namespace {

class DirectorySource : public PackageSource {
 public:
  explicit DirectorySource(const fs::path& root) : root_(root) {
    kind = "directory";
    std::error_code ec;
    for (fs::recursive_directory_iterator it(root, fs::directory_options::none, ec), end;
         !ec && it != end; it.increment(ec)) {
      paths_.push_back(it->path());
    }
    if (ec) throw Error(ErrorKind::Input, root.string(), kStep,
                        "cannot list the bag directory (" + ec.message() + ")");
    std::sort(paths_.begin(), paths_.end());
    for (const fs::path& p : paths_) {
      std::error_code sec;
      const auto st = fs::symlink_status(p, sec);
      if (!sec && fs::is_regular_file(st)) total_ += fs::file_size(p, sec);
    }
  }
  ~DirectorySource() override { close(); }

  bool next(RawEntry& entry) override {
    close();
    if (index_ >= paths_.size()) return false;
    const fs::path& p = paths_[index_++];
    entry = RawEntry{};
    entry.path = p.lexically_relative(root_).generic_string();
    struct stat st {};
    if (::lstat(p.c_str(), &st) != 0) {
      entry.type = EntryType::Other;
      entry.typeName = "an entry that vanished while reading";
      return true;
    }
    if (S_ISDIR(st.st_mode)) entry.type = EntryType::Directory;
    else if (S_ISLNK(st.st_mode)) { entry.type = EntryType::Symlink; entry.typeName = "a symbolic link"; }
    else if (S_ISREG(st.st_mode)) {
      entry.type = EntryType::File;
      // O_NOATIME where allowed (the owner, or root): a bag `audit` reads keeps its files' access times.
      fd_ = ::open(p.c_str(), O_RDONLY | O_NOFOLLOW | O_CLOEXEC | O_NONBLOCK | O_NOATIME);
      if (fd_ < 0 && errno == EPERM) fd_ = ::open(p.c_str(), O_RDONLY | O_NOFOLLOW | O_CLOEXEC | O_NONBLOCK);
      struct stat fst {};
      if (fd_ < 0 || ::fstat(fd_, &fst) != 0 || !S_ISREG(fst.st_mode))
        refuse(entry.path, "the file changed into something else while it was being read");
      entry.declaredSize = static_cast<std::uint64_t>(fst.st_size);
    } else {
      entry.type = EntryType::Other;
      entry.typeName = S_ISFIFO(st.st_mode)   ? "a FIFO"
                       : S_ISSOCK(st.st_mode) ? "a socket"
                                              : "a device file";
    }
    return true;
  }

  std::size_t read(char* buffer, std::size_t size) override {
    if (fd_ < 0) return 0;
    while (true) {
      const ssize_t n = ::read(fd_, buffer, size);
      if (n >= 0) { done_ += static_cast<std::uint64_t>(n); return static_cast<std::size_t>(n); }
      if (errno == EINTR) continue;
      throw Error(ErrorKind::Input, paths_[index_ - 1].string(), kStep,
                  std::string("cannot read the file (") + std::strerror(errno) + ")");
    }
  }
  double fraction() const override { return total_ ? double(done_) / double(total_) : 1.0; }
  std::uint64_t compressedBytes() const override { return 0; }

 private:
  void close() {
    if (fd_ >= 0) ::close(fd_);
    fd_ = -1;
  }
  fs::path root_;
  std::vector<fs::path> paths_;
  std::size_t index_ = 0;
  int fd_ = -1;
  std::uint64_t total_ = 0, done_ = 0;
};


}  // namespace

std::unique_ptr<PackageSource> openDirectorySource(const fs::path& root) {
  return std::make_unique<DirectorySource>(root);
}

}  // namespace surrogate::archive
