// A .tar (optionally compressed) or .zip as the package reader's source of entries, streamed
// through libarchive and never extracted. The file's bytes pass through a TarLayout on their
// way in (archive_end.h), so that a tar cut at an entry boundary or followed by other data is
// found in the same single read; a zip's end is checked once its entries are read. Every
// libarchive call of the reader is here; what the entries may be is checked for every
// container alike (entry_checks.cpp).
#include <archive.h>
#include <archive_entry.h>
#include <fcntl.h>
#include <locale.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <cstdio>
#include <cstring>
#include <vector>

#include "archive/archive_end.h"
#include "archive/entry_checks.h"
#include "archive/package.h"
#include "archive/package_source.h"
#include "core/error.h"

namespace fs = std::filesystem;

namespace surrogate::archive {

namespace {

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

// The bytes of the file pass through TarLayout on their way in (read callback).
class ArchiveSource : public PackageSource {
 public:
  explicit ArchiveSource(const fs::path& file) : file_(file) {
    const Utf8Names utf8;
    std::error_code ec;
    fileSize_ = fs::file_size(file, ec);
    // O_NOATIME where the system allows it (the file's owner, or root): reading a package, as
    // `audit` reads another's, leaves even its access time as it was.
    fd_.fd = ::open(file.c_str(), O_RDONLY | O_CLOEXEC | O_NOATIME);
    if (fd_.fd < 0 && errno == EPERM) fd_.fd = ::open(file.c_str(), O_RDONLY | O_CLOEXEC);
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
    current_ = entry.path;
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
      // The entry whose bytes are damaged, named: an audit of many packages says which file to
      // restore from another copy.
      damaged(file_.string(), why + ", in " + current_);
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
  std::string current_;  // the entry being read, as the archive names it
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

}  // namespace

std::unique_ptr<PackageSource> openArchiveSource(const fs::path& file) {
  return std::make_unique<ArchiveSource>(file);
}

std::string libarchiveVersion() {
  const std::string text = archive_version_string();  // "libarchive 3.6.2"
  const auto space = text.rfind(' ');
  return space == std::string::npos ? text : text.substr(space + 1);
}

}  // namespace surrogate::archive
