#include "core/atomic_file.h"

#include <fcntl.h>
#include <signal.h>
#include <stdio.h>
#include <unistd.h>

#include <algorithm>
#include <atomic>
#include <cerrno>
#include <cstring>
#include <fstream>
#include <sstream>
#include <streambuf>
#include <vector>

#include "core/error.h"
#include "core/resident.h"

namespace surrogate {

namespace fs = std::filesystem;

namespace {
fs::path temporaryNameFor(const fs::path& finalPath, const fs::path& folder) {
  static std::atomic<unsigned> counter{0};
  std::ostringstream name;
  name << "." << finalPath.filename().string() << ".part-" << ::getpid() << "-" << counter++;
  return folder / name.str();
}

// 0, or the errno of an fsync that failed: then the bytes may not all be on the disk (EIO, or
// ENOSPC and EDQUOT on file systems that allocate at writeback, such as NFS), and the file must
// not be renamed into place as if they were. A file system that cannot sync (EINVAL, EROFS) or
// a file that cannot be opened for it counts as synced, as the write itself succeeded.
int syncFile(const fs::path& path) {
  const int fd = ::open(path.c_str(), O_RDONLY | O_CLOEXEC);
  if (fd < 0) return 0;
  const int error = ::fsync(fd) == 0 || errno == EINVAL || errno == EROFS ? 0 : errno;
  ::close(fd);
  return error;
}
// Bytes gathered before a write(2): a PTM comes a row (a few KB) at a time.
constexpr std::size_t kBufferBytes = std::size_t{1} << 18;
// Writeback is started after each this many bytes, so commit()'s fsync has about this much left
// to wait for (the disk here takes about 1 ms a MB, the writer 3 ms a MB).
constexpr off_t kWritebackStride = off_t{1} << 20;

// A stream buffer over a new file that starts the disk's writeback of each stride as soon as
// it is written (sync_file_range with SYNC_FILE_RANGE_WRITE only: nothing waited for, so what
// the file holds on disk is promised by commit()'s fsync alone, as before). Keeps the first
// error met, which close() returns.
class WritebackBuffer : public std::streambuf {
 public:
  explicit WritebackBuffer(const fs::path& path) : buffer_(kBufferBytes) {
    fd_ = ::open(path.c_str(), O_WRONLY | O_CREAT | O_TRUNC | O_CLOEXEC, 0666);
    if (fd_ < 0) error_ = errno;
    setp(buffer_.data(), buffer_.data() + buffer_.size());
  }
  ~WritebackBuffer() override {
    if (fd_ >= 0) ::close(fd_);
  }
  WritebackBuffer(const WritebackBuffer&) = delete;
  WritebackBuffer& operator=(const WritebackBuffer&) = delete;

  // Writes what is buffered and closes the file; the first error met, or 0.
  int close() {
    drain();
    if (fd_ >= 0 && ::close(fd_) != 0 && !error_) error_ = errno;
    fd_ = -1;
    return error_;
  }

 protected:
  std::streamsize xsputn(const char* s, std::streamsize n) override {
    const auto size = static_cast<std::size_t>(n);
    if (size > static_cast<std::size_t>(epptr() - pptr())) {
      if (!drain()) return 0;
      // As large as the buffer: straight to the file, no copy.
      if (size >= buffer_.size()) return writeOut(s, size) ? n : 0;
    }
    std::memcpy(pptr(), s, size);
    pbump(static_cast<int>(size));
    return n;
  }
  int_type overflow(int_type c) override {
    if (!drain()) return traits_type::eof();
    if (!traits_type::eq_int_type(c, traits_type::eof())) {
      *pptr() = traits_type::to_char_type(c);
      pbump(1);
    }
    return traits_type::not_eof(c);
  }
  int sync() override { return drain() ? 0 : -1; }

 private:
  bool drain() {
    const auto n = static_cast<std::size_t>(pptr() - pbase());
    setp(buffer_.data(), buffer_.data() + buffer_.size());
    return writeOut(buffer_.data(), n);
  }
  // All `n` bytes, a stride at most per write(2), so that the writeback of a large block starts
  // while the rest of it is still being copied.
  bool writeOut(const char* s, std::size_t n) {
    while (n > 0 && !error_) {
      const ssize_t w = ::write(fd_, s, std::min<std::size_t>(n, kWritebackStride));
      if (w < 0 && errno == EINTR) continue;
      if (w <= 0) {
        error_ = w < 0 ? errno : EIO;
        break;
      }
      s += w;
      n -= static_cast<std::size_t>(w);
      written_ += w;
      if (written_ - started_ >= kWritebackStride) startWriteback();
    }
    return !error_;
  }
  // Whole pages only: a page still being filled would be written twice.
  void startWriteback() {
    static const off_t page = std::max<long>(::sysconf(_SC_PAGESIZE), 1);
    const off_t end = written_ / page * page;
    if (end <= started_) return;
    // Only advice: a file system without it (EINVAL, ENOSYS) is synced by commit() alone. A
    // disk that is full or failing is this write's error, as write(2)'s would be.
    if (::sync_file_range(fd_, started_, end - started_, SYNC_FILE_RANGE_WRITE) != 0 &&
        (errno == ENOSPC || errno == EDQUOT || errno == EIO)) {
      error_ = errno;
    }
    started_ = end;
  }

  std::vector<char> buffer_;
  int fd_ = -1;
  int error_ = 0;
  off_t written_ = 0;
  off_t started_ = 0;
};
}  // namespace

AtomicFile::AtomicFile(fs::path finalPath)
    : final_(std::move(finalPath)), temp_(temporaryNameFor(final_, final_.parent_path())) {}

AtomicFile::AtomicFile(fs::path finalPath, const fs::path& tempFolder)
    : final_(std::move(finalPath)), temp_(temporaryNameFor(final_, tempFolder)) {}

AtomicFile::~AtomicFile() {
  if (!committed_) {
    std::error_code ec;
    fs::remove_all(temp_, ec);
  }
}

void AtomicFile::commit() {
  if (fs::is_regular_file(temp_))
    if (const int error = syncFile(temp_)) throw writeError(final_, "write", error);
  std::error_code ec;
  fs::rename(temp_, final_, ec);
  if (ec) throw writeError(final_, "write", ec.value());
  committed_ = true;
}

void AtomicFile::commitWithoutReplacing() {
  std::error_code ec;
  const bool folder = fs::is_directory(temp_, ec);
  if (!folder)
    if (const int error = syncFile(temp_)) throw writeError(final_, "write", error);
  auto taken = [&] {
    return Error(ErrorKind::Input, final_.string(), "write",
                 "appeared while this was being written (another Surrogate writing to the same "
                 "name?); it was not replaced and what this command wrote was discarded: choose "
                 "another name, or remove the other and run again");
  };
  // An empty folder at the final name is replaced, as a plain rename does (and refuses, with
  // ENOTEMPTY or EEXIST, once something filled it).
  if (folder && fs::is_directory(final_, ec) && fs::is_empty(final_, ec)) {
    if (::rename(temp_.c_str(), final_.c_str()) != 0) {
      if (errno == ENOTEMPTY || errno == EEXIST) throw taken();
      throw writeError(final_, "write", errno);
    }
    committed_ = true;
    return;
  }
  if (::renameat2(AT_FDCWD, temp_.c_str(), AT_FDCWD, final_.c_str(), RENAME_NOREPLACE) == 0) {
    committed_ = true;
    return;
  }
  if (errno == EEXIST) throw taken();
  if (errno != EINVAL && errno != ENOSYS) throw writeError(final_, "write", errno);
  // A file system without RENAME_NOREPLACE: link(2) never replaces either.
  if (!folder) {
    if (::link(temp_.c_str(), final_.c_str()) != 0) {
      if (errno == EEXIST) throw taken();
      throw writeError(final_, "write", errno);
    }
    ::unlink(temp_.c_str());
    committed_ = true;
    return;
  }
  if (fs::exists(fs::symlink_status(final_, ec))) throw taken();
  if (::rename(temp_.c_str(), final_.c_str()) != 0) throw writeError(final_, "write", errno);
  committed_ = true;
}

std::vector<AbandonedTemporary> abandonedTemporaries(const fs::path& finalPath) {
  // temporaryNameFor's name: ".NAME.part-PID-N" in the same folder.
  const std::string prefix = "." + finalPath.filename().string() + ".part-";
  const fs::path folder = finalPath.parent_path().empty() ? fs::path(".") : finalPath.parent_path();
  std::vector<AbandonedTemporary> out;
  std::error_code ec;
  for (fs::directory_iterator it(folder, ec), end; !ec && it != end; it.increment(ec)) {
    const std::string name = it->path().filename().string();
    if (name.compare(0, prefix.size(), prefix) != 0) continue;
    const std::string rest = name.substr(prefix.size());  // "PID-N"
    const std::size_t dash = rest.find('-');
    if (dash == 0 || dash == std::string::npos || dash > 9 || dash + 1 == rest.size() ||
        !std::all_of(rest.begin(), rest.end(), [](char c) { return (c >= '0' && c <= '9') || c == '-'; }) ||
        rest.find('-', dash + 1) != std::string::npos)
      continue;
    const pid_t pid = static_cast<pid_t>(std::stol(rest.substr(0, dash)));
    // Alive (or not ours to signal): kept. Only "no such process" means it is gone.
    if (pid <= 0 || pid == ::getpid() || ::kill(pid, 0) == 0 || errno != ESRCH) continue;
    out.push_back({it->path(), static_cast<long>(pid)});
  }
  return out;
}

Error writeError(const fs::path& path, const std::string& step, int error) {
  std::string what;
  switch (error) {
    case ENOSPC:
    case EDQUOT:
      what = "the disk is full (" + std::string(std::strerror(error)) +
             "); free some space, or write somewhere else, and run again";
      break;
    case EFBIG:
      what = "the file is larger than this system allows (" + std::string(std::strerror(error)) +
             "; see `ulimit -f`); raise the limit or write somewhere that allows it";
      break;
    case EACCES:
    case EPERM:
      what = "permission denied: this user may not write there; choose a folder you can write to";
      break;
    case EROFS:
      what = "the file system is read-only; write somewhere else";
      break;
    default:
      what = std::string("it could not be written: ") + std::strerror(error);
  }
  return Error(ErrorKind::Input, path.string(), step, what + ". Nothing was left half-written under this name.");
}

void writeTemporary(const AtomicFile& file, const std::string& content) {
  errno = 0;
  std::ofstream f(file.tempPath(), std::ios::binary);
  f.write(content.data(), static_cast<std::streamsize>(content.size()));
  f.flush();
  if (!f) throw writeError(file.finalPath(), "write", errno ? errno : EIO);
  f.close();
  if (!f) throw writeError(file.finalPath(), "write", errno ? errno : EIO);
}

void writeTemporary(const AtomicFile& file, const std::string& step,
                    const std::function<void(std::ostream&)>& write) {
  WritebackBuffer buffer(file.tempPath());
  std::ostream out(&buffer);
  write(out);
  out.flush();
  const int error = buffer.close();
  if (error || !out) throw writeError(file.finalPath(), step, error ? error : EIO);
}

void writeFileAtomically(const fs::path& path, const std::string& content, const fs::path& tempFolder) {
  AtomicFile out(path, tempFolder.empty() ? path.parent_path() : tempFolder);
  writeTemporary(out, content);
  out.commit();
}

std::string readFile(const fs::path& path, const std::string& step) {
  std::ifstream f(path, std::ios::binary);
  if (!f) throwInputError(path.string(), step, "cannot open the file for reading");
  // One read of the size the file says it has, straight into the string (a stream copy grows
  // and copies a photograph's bytes several times); then whatever is left, if it has grown or
  // has no size to tell (a pipe).
  std::error_code ec;
  const std::uintmax_t size = fs::file_size(path, ec);
  std::string out;
  resizeResident(out, ec ? 0 : static_cast<std::size_t>(size));
  f.read(out.data(), static_cast<std::streamsize>(out.size()));
  out.resize(static_cast<std::size_t>(f.gcount()));
  char more[65536];
  while (f && f.read(more, sizeof more).gcount() > 0) out.append(more, static_cast<std::size_t>(f.gcount()));
  if (f.bad()) throwInputError(path.string(), step, "reading the file failed");
  return out;
}

}  // namespace surrogate
