#include "archive/package_reader.h"

#include <archive.h>
#include <archive_entry.h>
#include <fcntl.h>
#include <locale.h>
#include <sys/stat.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <cstring>
#include <memory>
#include <optional>
#include <vector>

#include "archive/bag_text.h"
#include "core/digest.h"
#include "core/error.h"
#include "core/file_names.h"

namespace fs = std::filesystem;

namespace surrogate::archive {

namespace {

constexpr const char* kStep = "verify";
constexpr std::uint64_t kMaxKeptBytes = 512ull << 20;  // all tag files held in memory

[[noreturn]] void refuse(const std::string& where, const std::string& why) {
  throw Error(ErrorKind::Usage, where, kStep,
              why + "; the package was refused without extracting anything (it is not a "
                    "package Surrogate wrote, or it was altered)");
}

[[noreturn]] void damaged(const std::string& where, const std::string& why) {
  throw Error(ErrorKind::Fixity, where, kStep,
              "the archive is truncated or damaged (" + why +
                  "); get a fresh copy of the package from its source");
}

[[noreturn]] void trailing(const std::string& where, const std::string& why) {
  throw Error(ErrorKind::Fixity, where, kStep,
              "data follow the end of the archive (" + why +
                  "); they are covered by no manifest and are not part of the package (another "
                  "archive appended?): get a fresh copy of the package from its source");
}

// The block structure of an uncompressed tar, followed byte by byte as the archive is read
// (libarchive takes an archive cut at an entry boundary, or followed by a second archive, for a
// whole one): 512-byte headers, each followed by its data padded to 512 bytes, then the
// end-of-archive marker (two zero blocks), then only whole 512-byte blocks of zeros (the padding
// of the last record).
class TarLayout {
 public:
  void feed(const char* data, std::size_t n) {
    while (n > 0) {
      if (skip_ > 0) {  // an entry's data and padding
        const std::size_t take = static_cast<std::size_t>(std::min<std::uint64_t>(skip_, n));
        if (collect_ > 0) {
          const std::size_t keep = static_cast<std::size_t>(std::min<std::uint64_t>(collect_, take));
          pax_.append(data, keep);
          collect_ -= keep;
        }
        skip_ -= take;
        data += take;
        n -= take;
        offset_ += take;
        if (skip_ == 0 && collecting_) {
          collecting_ = false;
          paxSize_ = paxSize(pax_);
          pax_.clear();
        }
        continue;
      }
      if (state_ == State::Padding) {  // after the end marker: zeros only
        if (!trailingAt_) {
          for (std::size_t i = 0; i < n; ++i)
            if (data[i] != 0) {
              trailingAt_ = offset_ + i;
              break;
            }
        }
        offset_ += n;
        return;
      }
      const std::size_t take = std::min(n, 512 - block_.size());
      block_.append(data, take);
      data += take;
      n -= take;
      offset_ += take;
      if (block_.size() == 512) {
        header(offset_ - 512);
        block_.clear();
      }
    }
  }

  // Why the archive that ended after everything fed is not whole, or "" when it is.
  // `truncation` says which kind: true for a cut, false for data after the end.
  std::string problem(bool& truncation) const {
    truncation = true;
    if (broken_) return *broken_;
    if (skip_ > 0 || !block_.empty())
      return "it ends inside an entry or a 512-byte block, at byte " + std::to_string(offset_);
    if (state_ == State::Header)
      return "it ends at byte " + std::to_string(offset_) +
             " without the tar end-of-archive marker: it was cut at an entry boundary";
    if (state_ == State::SecondZero)
      return "it ends after the first of the two end-of-archive blocks";
    if (trailingAt_) {
      truncation = false;
      return std::to_string(offset_ - *trailingAt_) + " bytes from byte " +
             std::to_string(*trailingAt_) + ", after the end-of-archive marker at byte " +
             std::to_string(endAt_);
    }
    // After the marker, writers pad with zeros to the end of their last record, whose size
    // varies (10240 bytes for most, pack's are larger): only whole 512-byte blocks of zeros.
    if (offset_ % 512 != 0)
      return "it ends inside a 512-byte block of its end padding, at byte " + std::to_string(offset_);
    return "";
  }

 private:
  enum class State { Header, SecondZero, Padding };

  static bool zero(const std::string& block) {
    return std::all_of(block.begin(), block.end(), [](char c) { return c == 0; });
  }

  // A numeric header field: octal digits (leading spaces or NULs), or base-256 (GNU, high bit).
  static std::optional<std::uint64_t> number(const char* field, std::size_t size) {
    const auto* u = reinterpret_cast<const unsigned char*>(field);
    if (u[0] & 0x80) {
      if (u[0] != 0x80) return std::nullopt;  // negative or too large
      std::uint64_t v = 0;
      for (std::size_t i = 1; i < size; ++i) {
        if (v >> 56) return std::nullopt;
        v = (v << 8) | u[i];
      }
      return v;
    }
    std::size_t i = 0;
    while (i < size && (field[i] == ' ' || field[i] == 0)) ++i;
    std::uint64_t v = 0;
    bool digits = false;
    for (; i < size && field[i] >= '0' && field[i] <= '7'; ++i) {
      v = v * 8 + static_cast<std::uint64_t>(field[i] - '0');
      digits = true;
    }
    for (; i < size; ++i)
      if (field[i] != ' ' && field[i] != 0) return std::nullopt;
    return digits ? std::optional<std::uint64_t>(v) : std::optional<std::uint64_t>(0);
  }

  // "size=" of a pax extended header ("<length> <key>=<value>\n" records), if it has one.
  static std::optional<std::uint64_t> paxSize(const std::string& text) {
    std::size_t at = 0;
    while (at < text.size()) {
      const std::size_t space = text.find(' ', at);
      if (space == std::string::npos) break;
      const std::uint64_t length = std::strtoull(text.c_str() + at, nullptr, 10);
      // The record holds its own "<length> " and ends with a newline, inside the text.
      if (length <= space - at + 1 || length > text.size() - at) break;
      const std::string record = text.substr(space + 1, at + length - space - 2);
      if (record.compare(0, 5, "size=") == 0) {
        const std::string digits = record.substr(5);
        if (!digits.empty() && digits.size() < 20 &&
            std::all_of(digits.begin(), digits.end(), [](char c) { return c >= '0' && c <= '9'; }))
          return std::strtoull(digits.c_str(), nullptr, 10);
      }
      at += length;
    }
    return std::nullopt;
  }

  void header(std::uint64_t at) {
    if (zero(block_)) {
      if (state_ == State::Header) {
        endAt_ = at;
        state_ = State::SecondZero;
      } else {
        state_ = State::Padding;
      }
      return;
    }
    if (state_ == State::SecondZero) {  // one zero block, then more: what follows is not ours
      trailingAt_ = at;
      state_ = State::Padding;
      return;
    }
    const auto size = number(block_.data() + 124, 12);
    if (!size) {
      if (!broken_) broken_ = "the tar header at byte " + std::to_string(at) + " is malformed";
      state_ = State::Padding;
      return;
    }
    const char type = block_[156];
    std::uint64_t bytes = *size;
    if (type == 'x' || type == 'g' || type == 'L' || type == 'K') {
      if (type == 'x' && bytes <= (1u << 20)) {
        collecting_ = true;
        collect_ = bytes;
        pax_.clear();
      }
    } else {
      if (paxSize_) bytes = *paxSize_;
      paxSize_.reset();
      // Links, devices, folders and FIFOs have no data blocks.
      if (type >= '1' && type <= '6') bytes = 0;
    }
    skip_ = (bytes + 511) / 512 * 512;
    if (skip_ == 0 && collecting_) {
      collecting_ = false;
      collect_ = 0;
    }
  }

  State state_ = State::Header;
  std::string block_;
  std::uint64_t offset_ = 0, skip_ = 0, collect_ = 0, endAt_ = 0;
  bool collecting_ = false;
  std::string pax_;
  std::optional<std::uint64_t> paxSize_, trailingAt_;
  std::optional<std::string> broken_;
};

// The end of a zip: the end-of-central-directory record (and, for zip64, its locator and
// record) must end exactly at the end of the file, and the central directory must end where
// they begin. Returns why not, or "" when it is whole; `truncation` says which kind.
std::string zipEndProblem(int fd, std::uint64_t fileSize, std::uint64_t entriesRead, bool& truncation) {
  truncation = true;
  auto u16 = [](const unsigned char* p) { return std::uint64_t(p[0]) | std::uint64_t(p[1]) << 8; };
  auto u32 = [&](const unsigned char* p) { return u16(p) | u16(p + 2) << 16; };
  auto u64 = [&](const unsigned char* p) { return u32(p) | u32(p + 4) << 32; };
  const std::uint64_t tail = std::min<std::uint64_t>(fileSize, 22 + 65535);
  std::vector<unsigned char> buffer(static_cast<std::size_t>(tail));
  if (tail < 22 || ::pread(fd, buffer.data(), buffer.size(), static_cast<off_t>(fileSize - tail)) !=
                       static_cast<ssize_t>(tail))
    return "it is too short to hold a zip end-of-central-directory record";
  const std::uint64_t base = fileSize - tail;
  // The last record whose comment reaches at least to its own end; its end must be the file's.
  for (std::size_t i = buffer.size() - 22 + 1; i-- > 0;) {
    const unsigned char* p = buffer.data() + i;
    if (u32(p) != 0x06054b50) continue;
    const std::uint64_t at = base + i;
    const std::uint64_t end = at + 22 + u16(p + 20);
    if (end > fileSize) continue;  // a signature inside other data, or a cut comment
    if (end < fileSize) {
      truncation = false;
      return std::to_string(fileSize - end) + " bytes after the end-of-central-directory record at byte " +
             std::to_string(at);
    }
    std::uint64_t entries = u16(p + 10), cdSize = u32(p + 12), cdOffset = u32(p + 16);
    std::uint64_t cdEnd = at;
    if (entries == 0xFFFF || cdSize == 0xFFFFFFFF || cdOffset == 0xFFFFFFFF) {
      unsigned char locator[20], record[56];
      if (at < 20 || ::pread(fd, locator, 20, static_cast<off_t>(at - 20)) != 20 ||
          u32(locator) != 0x07064b50)
        return "its zip64 end-of-central-directory locator is missing";
      const std::uint64_t recordAt = u64(locator + 8);
      if (recordAt + 56 > at - 20 || ::pread(fd, record, 56, static_cast<off_t>(recordAt)) != 56 ||
          u32(record) != 0x06064b50)
        return "its zip64 end-of-central-directory record is missing";
      entries = u64(record + 32);
      cdSize = u64(record + 40);
      cdOffset = u64(record + 48);
      cdEnd = recordAt;
    }
    if (cdOffset + cdSize != cdEnd) {
      // A whole zip followed by another one: the last end record repeats the offsets of the
      // first (each zip counts from its own start), whose end record then follows its central
      // directory, before the end of the file.
      unsigned char first[22];
      const std::uint64_t firstAt = cdOffset + cdSize;
      if (firstAt + 22 <= at && ::pread(fd, first, 22, static_cast<off_t>(firstAt)) == 22 &&
          u32(first) == 0x06054b50 && u32(first + 16) + u32(first + 12) == firstAt) {
        const std::uint64_t firstEnd = firstAt + 22 + u16(first + 20);
        if (firstEnd < fileSize) {
          truncation = false;
          return std::to_string(fileSize - firstEnd) +
                 " bytes after the end-of-central-directory record at byte " + std::to_string(firstAt);
        }
      }
      return "its central directory (" + std::to_string(cdSize) + " bytes at byte " +
             std::to_string(cdOffset) + ") does not end where the end record begins (byte " +
             std::to_string(cdEnd) + ")";
    }
    if (entries != entriesRead)
      return "its central directory lists " + std::to_string(entries) + " entries, " +
             std::to_string(entriesRead) + " were read";
    return "";
  }
  return "it does not end with a zip end-of-central-directory record: it was cut short, or "
         "other data follow it";
}

enum class EntryType { File, Directory, Symlink, Hardlink, Other };

struct RawEntry {
  std::string path;
  EntryType type = EntryType::Other;
  std::string typeName;
  std::optional<std::uint64_t> declaredSize;
};

class Source {
 public:
  virtual ~Source() = default;
  virtual bool next(RawEntry& entry) = 0;
  // Reads the current entry's content; 0 at its end.
  virtual std::size_t read(char* buffer, std::size_t size) = 0;
  virtual double fraction() const = 0;
  virtual std::uint64_t compressedBytes() const = 0;  // 0: not an archive
  std::string kind;
};

// A bag directory: walked without following links, sorted, files opened with O_NOFOLLOW.
class DirectorySource : public Source {
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
      fd_ = ::open(p.c_str(), O_RDONLY | O_NOFOLLOW | O_CLOEXEC | O_NONBLOCK);
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

// While alive, this thread reads and converts text as UTF-8 (LC_CTYPE C.UTF-8, the rest of the
// locale as it was). libarchive converts each entry's name to the locale's character set: in
// the "C" locale the program runs in, a zip entry's UTF-8 name ("naïve.txt") had no form, and
// every package holding a name beyond ASCII was refused as "not valid text". Thread-local
// (uselocale), so nothing else in the process sees it.
class Utf8Names {
 public:
  Utf8Names() {
    static const locale_t utf8 = newlocale(LC_CTYPE_MASK, "C.UTF-8", static_cast<locale_t>(nullptr));
    if (utf8) saved_ = uselocale(utf8);
  }
  ~Utf8Names() {
    if (saved_) uselocale(saved_);
  }
  Utf8Names(const Utf8Names&) = delete;
  Utf8Names& operator=(const Utf8Names&) = delete;

 private:
  locale_t saved_ = static_cast<locale_t>(nullptr);
};

// A .tar (optionally compressed) or .zip, streamed through libarchive. The bytes of the file
// pass through TarLayout on their way in (read callback), so that a tar cut at an entry
// boundary, or followed by other data, is found in the same single read.
class ArchiveSource : public Source {
 public:
  explicit ArchiveSource(const fs::path& file) : file_(file) {
    const Utf8Names utf8;
    std::error_code ec;
    fileSize_ = fs::file_size(file, ec);
    fd_.fd = ::open(file.c_str(), O_RDONLY | O_CLOEXEC);
    if (fd_.fd < 0)
      throw Error(ErrorKind::Input, file.string(), kStep,
                  std::string("cannot be opened (") + std::strerror(errno) + ")");
    a_.reset(archive_read_new());
    if (!a_) throw Error(ErrorKind::Internal, file.string(), kStep, "libarchive could not start");
    archive_read_support_filter_all(a_.get());
    archive_read_support_format_tar(a_.get());
    archive_read_support_format_gnutar(a_.get());
    archive_read_support_format_zip(a_.get());
    buffer_.resize(64 * 1024);
    archive_read_set_callback_data(a_.get(), this);
    archive_read_set_read_callback(a_.get(), &ArchiveSource::readCallback);
    archive_read_set_seek_callback(a_.get(), &ArchiveSource::seekCallback);
    if (archive_read_open1(a_.get()) != ARCHIVE_OK)
      notAPackage(archive_error_string(a_.get()) ? archive_error_string(a_.get()) : "unreadable");
  }

  bool next(RawEntry& entry) override {
    const Utf8Names utf8;
    archive_entry* e = nullptr;
    const int r = archive_read_next_header(a_.get(), &e);
    if (r == ARCHIVE_EOF) {
      checkEnd();
      return false;
    }
    if (r < ARCHIVE_WARN) {
      const std::string why = archive_error_string(a_.get()) ? archive_error_string(a_.get()) : "unreadable";
      if (first_) notAPackage(why);
      damaged(file_.string(), why);
    }
    if (first_) {
      const int base = archive_format(a_.get()) & ARCHIVE_FORMAT_BASE_MASK;
      kind = base == ARCHIVE_FORMAT_ZIP ? "zip" : base == ARCHIVE_FORMAT_TAR ? "tar"
                                                : archive_format_name(a_.get());
    }
    first_ = false;
    ++entries_;
    entry = RawEntry{};
    const char* name = archive_entry_pathname_utf8(e);
    if (!name) name = archive_entry_pathname(e);
    if (!name) refuse(file_.string(), "an entry has a name that is not valid text");
    entry.path = name;
    if (entry.path.size() > 1 && entry.path.back() == '/') entry.path.pop_back();
    const unsigned type = archive_entry_filetype(e);
    if (archive_entry_hardlink(e)) {
      entry.type = EntryType::Hardlink;
      entry.typeName = "a hard link";
    } else if (type == AE_IFREG) {
      entry.type = EntryType::File;
    } else if (type == AE_IFDIR) {
      entry.type = EntryType::Directory;
    } else if (type == AE_IFLNK) {
      entry.type = EntryType::Symlink;
      entry.typeName = "a symbolic link";
    } else {
      entry.type = EntryType::Other;
      entry.typeName = type == AE_IFIFO ? "a FIFO" : type == AE_IFSOCK ? "a socket"
                                                   : "a device file";
    }
    if (archive_entry_size_is_set(e) && archive_entry_size(e) >= 0)
      entry.declaredSize = static_cast<std::uint64_t>(archive_entry_size(e));
    return true;
  }

  std::size_t read(char* buffer, std::size_t size) override {
    const Utf8Names utf8;
    const la_ssize_t n = archive_read_data(a_.get(), buffer, size);
    if (n < 0) {
      const std::string why = archive_error_string(a_.get()) ? archive_error_string(a_.get()) : "unreadable";
      damaged(file_.string(), why);
    }
    return static_cast<std::size_t>(n);
  }
  double fraction() const override {
    return fileSize_ ? std::min(1.0, double(compressedBytes()) / double(fileSize_)) : 1.0;
  }
  std::uint64_t compressedBytes() const override {
    const la_int64_t n = archive_filter_bytes(a_.get(), -1);
    return n > 0 ? static_cast<std::uint64_t>(n) : 1;
  }

 private:
  static la_ssize_t readCallback(::archive*, void* self, const void** data) {
    auto* s = static_cast<ArchiveSource*>(self);
    ssize_t n;
    do {
      n = ::read(s->fd_.fd, s->buffer_.data(), s->buffer_.size());
    } while (n < 0 && errno == EINTR);
    if (n < 0) return -1;
    *data = s->buffer_.data();
    if (s->sequential_) s->tar_.feed(s->buffer_.data(), static_cast<std::size_t>(n));
    return n;
  }
  static la_int64_t seekCallback(::archive*, void* self, la_int64_t offset, int whence) {
    auto* s = static_cast<ArchiveSource*>(self);
    s->sequential_ = false;  // a zip read through its central directory: not a tar
    const off_t at = ::lseek(s->fd_.fd, static_cast<off_t>(offset), whence);
    return at < 0 ? ARCHIVE_FATAL : static_cast<la_int64_t>(at);
  }

  // At the end of the entries: is the archive whole, and is nothing after it?
  void checkEnd() {
    if (first_) return;  // an empty archive: the bag checks say what is missing
    bool truncation = true;
    std::string why;
    const int base = archive_format(a_.get()) & ARCHIVE_FORMAT_BASE_MASK;
    const bool uncompressed = archive_filter_code(a_.get(), 0) == ARCHIVE_FILTER_NONE;
    if (base == ARCHIVE_FORMAT_TAR && uncompressed) {
      // The rest of the file (libarchive stops reading at the end marker).
      std::vector<char> rest(64 * 1024);
      ssize_t n;
      while (sequential_ && (n = ::read(fd_.fd, rest.data(), rest.size())) != 0) {
        if (n < 0 && errno == EINTR) continue;
        if (n < 0) damaged(file_.string(), std::strerror(errno));
        tar_.feed(rest.data(), static_cast<std::size_t>(n));
      }
      if (sequential_) why = tar_.problem(truncation);
    } else if (base == ARCHIVE_FORMAT_ZIP && uncompressed) {
      why = zipEndProblem(fd_.fd, fileSize_, entries_, truncation);
    }
    if (why.empty()) return;
    if (truncation) damaged(file_.string(), why);
    trailing(file_.string(), why);
  }

  [[noreturn]] void notAPackage(const std::string& why) {
    // A file that starts like a tar or zip but cannot be read is damaged; anything else is
    // not a package at all.
    char head[512] = {};
    FILE* f = std::fopen(file_.c_str(), "rb");
    std::size_t n = f ? std::fread(head, 1, sizeof head, f) : 0;
    if (f) std::fclose(f);
    const bool zip = n >= 4 && std::memcmp(head, "PK", 2) == 0;
    const bool tar = n >= 262 && std::memcmp(head + 257, "ustar", 5) == 0;
    if (zip || tar) damaged(file_.string(), why);
    throw Error(ErrorKind::Usage, file_.string(), kStep,
                "is not a bag directory, a .tar or a .zip (" + why +
                    "); give the package Surrogate wrote with `surrogate pack`");
  }
  fs::path file_;
  struct Fd {
    int fd = -1;
    ~Fd() {
      if (fd >= 0) ::close(fd);
    }
  };
  struct Free {
    void operator()(::archive* a) const { archive_read_free(a); }
  };
  // Owned from the start, so a constructor that throws (not a package) closes and frees them
  // too; the file outlives the reader.
  Fd fd_;
  std::unique_ptr<::archive, Free> a_;
  std::uint64_t fileSize_ = 0, entries_ = 0;
  bool first_ = true;
  std::vector<char> buffer_;
  bool sequential_ = true;
  TarLayout tar_;
};

std::unique_ptr<Source> openSource(const fs::path& package) {
  std::error_code ec;
  const auto st = fs::symlink_status(package, ec);
  if (ec || !fs::exists(st))
    throw Error(ErrorKind::Input, package.string(), kStep,
                "does not exist; give a bag directory, .tar or .zip");
  if (fs::is_directory(fs::status(package, ec))) return std::make_unique<DirectorySource>(package);
  if (!fs::is_regular_file(fs::status(package, ec)))
    throw Error(ErrorKind::Usage, package.string(), kStep,
                "is not a directory or a regular file; give a bag directory, .tar or .zip");
  return std::make_unique<ArchiveSource>(package);
}

// Checks an entry's name and type; returns the normalised path.
std::string checkedEntry(const RawEntry& entry, const std::string& package, const Limits& limits) {
  std::string why;
  const auto path = safeBagPath(entry.path, &why, limits.maxPathLength);
  const std::string shown = entry.path.substr(0, 200);
  if (!path) refuse(package, "entry \"" + shown + "\": " + why);
  if (entry.type == EntryType::Symlink || entry.type == EntryType::Hardlink ||
      entry.type == EntryType::Other)
    refuse(package, "entry \"" + shown + "\" is " + entry.typeName +
                        "; a package holds regular files and folders only");
  return *path;
}

bool endsWith(const std::string& path, const std::string& tail) {
  return path.size() >= tail.size() && path.compare(path.size() - tail.size(), tail.size(), tail) == 0 &&
         (path.size() == tail.size() || path[path.size() - tail.size() - 1] == '/');
}

bool keepContent(const std::string& path) {
  const std::size_t slash = path.find('/');
  const std::string first = path.substr(0, slash);
  std::string second;
  if (slash != std::string::npos) second = path.substr(slash + 1, path.find('/', slash + 1) - slash - 1);
  const bool payload = first == "data" || second == "data";
  // The derived metadata can be hundreds of MB (4 KB per payload file): compared by digest.
  if (!payload) return !endsWith(path, "metadata/mets.xml") && !endsWith(path, "metadata/crm.rdf");
  return endsWith(path, "data/assembly-files/carrier.xml");
}

// Reads one entry's content, enforcing the size limits; feeds `sink`.
template <typename Sink>
std::uint64_t pump(Source& source, const RawEntry& entry, const std::string& path,
                   const Limits& limits, std::uint64_t& total, Sink&& sink) {
  // One buffer for every entry (allocating and clearing 256 KiB per file cost more than
  // reading a small file).
  static thread_local std::vector<char> buffer(256 * 1024);
  std::uint64_t bytes = 0;
  while (std::size_t n = source.read(buffer.data(), buffer.size())) {
    bytes += n;
    total += n;
    if (entry.declaredSize && bytes > *entry.declaredSize)
      refuse(path, "the entry holds more bytes than its header claims (" +
                       std::to_string(*entry.declaredSize) + ")");
    if (bytes > limits.maxEntryBytes)
      refuse(path, "the file is larger than the limit of " +
                       std::to_string(limits.maxEntryBytes) + " bytes");
    if (total > limits.maxTotalBytes)
      refuse(path, "the package holds more than the limit of " +
                       std::to_string(limits.maxTotalBytes) + " bytes");
    const std::uint64_t packed = source.compressedBytes();
    if (packed > 0 && total > limits.ratioFloorBytes &&
        double(total) > limits.maxRatio * double(packed))
      refuse(path, "the archive expands more than " + std::to_string(int(limits.maxRatio)) +
                       " times (a decompression bomb?)");
    sink(buffer.data(), n);
  }
  return bytes;
}

}  // namespace

Inventory readPackage(const fs::path& package, const Limits& limits, const Progress& progress,
                      bool legacyDigests) {
  std::vector<DigestAlgorithm> algorithms = {DigestAlgorithm::Sha256, DigestAlgorithm::Sha512};
  if (legacyDigests) {
    algorithms.push_back(DigestAlgorithm::Md5);
    algorithms.push_back(DigestAlgorithm::Sha1);
  }
  std::unique_ptr<Source> source = openSource(package);
  const std::string name = package.string();
  Inventory raw;
  std::map<std::string, std::string> folded;  // case-fold key -> path
  std::uint64_t entries = 0, total = 0, kept = 0;
  const std::string label = "reading " + package.filename().string();
  RawEntry entry;
  while (source->next(entry)) {
    if (++entries > limits.maxEntries)
      refuse(name, "the package has more than " + std::to_string(limits.maxEntries) + " entries");
    const std::string path = checkedEntry(entry, name, limits);
    const auto [it, fresh] = folded.emplace(caseFoldKey(path), path);
    if (!fresh && it->second != path)
      refuse(name, "entries \"" + it->second + "\" and \"" + path +
                       "\" differ only in letter case or Unicode normalisation and would "
                       "overwrite each other on Windows or macOS");
    if (entry.type == EntryType::Directory) {
      if (raw.files.count(path)) refuse(name, "\"" + path + "\" is both a file and a folder");
      raw.directories.insert(path);
      continue;
    }
    if (!fresh || raw.files.count(path) || raw.directories.count(path))
      refuse(name, "entry \"" + path + "\" appears twice; a later copy could silently replace "
                   "the first");
    InventoryFile file;
    MultiDigest digest(algorithms);
    const bool keep = keepContent(path);
    std::string content;
    if (keep && entry.declaredSize && *entry.declaredSize <= limits.maxTagFileBytes)
      content.reserve(static_cast<std::size_t>(*entry.declaredSize));
    file.size = pump(*source, entry, path, limits, total, [&](const char* data, std::size_t n) {
      digest.update(data, n);
      if (keep && content.size() <= limits.maxTagFileBytes) content.append(data, n);
      if (progress) progress(label, source->fraction());  // a large file moves the bar too
    });
    file.sha256 = digest.hex(DigestAlgorithm::Sha256);
    file.sha512 = digest.hex(DigestAlgorithm::Sha512);
    if (legacyDigests) {
      file.md5 = digest.hex(DigestAlgorithm::Md5);
      file.sha1 = digest.hex(DigestAlgorithm::Sha1);
    }
    if (keep && content.size() <= limits.maxTagFileBytes) {
      kept += content.size();
      if (kept > kMaxKeptBytes)
        refuse(name, "the package's tag files are larger than " +
                         std::to_string(kMaxKeptBytes) + " bytes in all");
      file.content = std::move(content);
    }
    raw.files.emplace(path, std::move(file));
  }
  // The last entry's end is not the archive's: a .zip's central directory follows it.
  if (progress) progress(label, 1);
  // A file must not also be a folder of other entries ("a" and "a/b").
  for (const auto& [path, file] : raw.files) {
    for (std::size_t slash = path.find('/'); slash != std::string::npos;
         slash = path.find('/', slash + 1))
      if (raw.files.count(path.substr(0, slash)))
        refuse(name, "\"" + path.substr(0, slash) + "\" is both a file and a folder");
  }

  Inventory inv;
  inv.kind = source->kind;
  inv.totalBytes = total;
  if (!raw.files.count("bagit.txt") && source->kind != "directory") {
    // Archives usually hold the bag in one top folder: "stela/bagit.txt".
    std::set<std::string> tops;
    for (const auto& [p, f] : raw.files) tops.insert(p.substr(0, p.find('/')));
    for (const auto& d : raw.directories) tops.insert(d.substr(0, d.find('/')));
    if (tops.size() == 1 && raw.files.count(*tops.begin() + "/bagit.txt"))
      inv.rootPrefix = *tops.begin() + "/";
  }
  const std::size_t cut = inv.rootPrefix.size();
  for (auto& [p, f] : raw.files) inv.files.emplace(p.substr(cut), std::move(f));
  for (const auto& d : raw.directories)
    if (d.size() > cut) inv.directories.insert(d.substr(cut));
  return inv;
}

std::string readBagFile(const fs::path& package, const Inventory& inventory, const std::string& path,
                        const Limits& limits) {
  const auto known = inventory.files.find(path);
  if (known == inventory.files.end())
    throw Error(ErrorKind::Internal, path, kStep, "is not a file of the package");
  std::unique_ptr<Source> source = openSource(package);
  std::uint64_t total = 0;
  RawEntry entry;
  while (source->next(entry)) {
    const std::string full = checkedEntry(entry, package.string(), limits);
    if (entry.type != EntryType::File || full != inventory.rootPrefix + path) continue;
    std::string content;
    content.reserve(static_cast<std::size_t>(known->second.size));
    MultiDigest digest({DigestAlgorithm::Sha256});
    pump(*source, entry, path, limits, total, [&](const char* data, std::size_t n) {
      digest.update(data, n);
      content.append(data, n);
    });
    if (digest.hex(DigestAlgorithm::Sha256) != known->second.sha256)
      throw Error(ErrorKind::Fixity, path, kStep,
                  "the file changed between two reads of the package; is something writing to it?");
    return content;
  }
  throw Error(ErrorKind::Fixity, path, kStep,
              "the file vanished between two reads of the package; is something writing to it?");
}

void extractFiles(const fs::path& package, const Inventory& inventory, const fs::path& destination,
                  const std::function<fs::path(const std::string&)>& targetOf,
                  const Limits& limits, const Progress& progress) {
  std::unique_ptr<Source> source = openSource(package);
  std::uint64_t total = 0;
  RawEntry entry;
  while (source->next(entry)) {
    const std::string full = checkedEntry(entry, package.string(), limits);
    if (entry.type != EntryType::File) continue;
    if (full.compare(0, inventory.rootPrefix.size(), inventory.rootPrefix) != 0) continue;
    const std::string path = full.substr(inventory.rootPrefix.size());
    const auto known = inventory.files.find(path);
    if (known == inventory.files.end() && inventory.setAside.count(path)) continue;
    if (known == inventory.files.end())
      damaged(package.string(), "\"" + path + "\" appeared between two reads of the package");
    const fs::path relative = targetOf(path);
    if (relative.empty()) continue;
    std::string why;
    if (!safeBagPath(relative.generic_string(), &why))
      throw Error(ErrorKind::Internal, relative.string(), kStep, "unsafe extraction target: " + why);
    // Create the folders one by one, refusing anything that is not a real folder we made.
    fs::path dir = destination;
    for (auto it = relative.begin(); std::next(it) != relative.end(); ++it) {
      dir /= *it;
      if (::mkdir(dir.c_str(), 0755) != 0 && errno != EEXIST)
        throw Error(ErrorKind::Internal, dir.string(), kStep,
                    std::string("cannot create a temporary folder (") + std::strerror(errno) + ")");
      struct stat st {};
      if (::lstat(dir.c_str(), &st) != 0 || !S_ISDIR(st.st_mode))
        refuse(path, "a folder of the extraction is not a plain folder");
    }
    const fs::path target = destination / relative;
    const int fd = ::open(target.c_str(), O_WRONLY | O_CREAT | O_EXCL | O_NOFOLLOW | O_CLOEXEC, 0644);
    if (fd < 0)
      throw Error(ErrorKind::Internal, target.string(), kStep,
                  std::string("cannot write the temporary copy (") + std::strerror(errno) +
                      "); is the temporary folder full? set TMPDIR to a larger disk");
    MultiDigest digest({DigestAlgorithm::Sha256});
    bool writeFailed = false;
    try {
      pump(*source, entry, path, limits, total, [&](const char* data, std::size_t n) {
        digest.update(data, n);
        while (n > 0 && !writeFailed) {
          const ssize_t w = ::write(fd, data, n);
          if (w < 0 && errno == EINTR) continue;
          if (w <= 0) { writeFailed = true; break; }
          data += w;
          n -= static_cast<std::size_t>(w);
        }
      });
    } catch (...) {
      ::close(fd);
      throw;
    }
    ::close(fd);
    if (writeFailed)
      throw Error(ErrorKind::Internal, target.string(), kStep,
                  "cannot write the temporary copy (disk full?); set TMPDIR to a larger disk");
    if (digest.hex(DigestAlgorithm::Sha256) != known->second.sha256)
      throw Error(ErrorKind::Fixity, path, kStep,
                  "the file changed between two reads of the package; is something writing to it?");
    if (progress) progress("extracting for re-execution", source->fraction());
  }
  if (progress) progress("extracting for re-execution", 1);
}

}  // namespace surrogate::archive
