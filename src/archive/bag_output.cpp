// The output of a bag: its name (.tar, .zip or a folder), the checks made on it before any work,
// the partial outputs of killed packs, and the sinks that write entries with fixed owner,
// permissions and times into a folder or through libarchive. Every libarchive call of the
// writer is here, so that the rest of the writer (bag.cpp) is the same for all three outputs.
#include "archive/bag_output.h"

#include <archive.h>
#include <archive_entry.h>
#include <fcntl.h>
#include <locale.h>
#include <signal.h>
#include <sys/stat.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <cstdlib>
#include <optional>
#include <vector>

#include "archive/bag_text.h"
#include "core/atomic_file.h"
#include "core/error.h"
#include "core/file_names.h"
#include "core/text.h"

namespace surrogate::archive {

namespace fs = std::filesystem;

BagFormat bagFormatFor(const fs::path& out) {
  std::string ext = out.extension().string();
  std::transform(ext.begin(), ext.end(), ext.begin(), [](unsigned char c) { return std::tolower(c); });
  if (ext == ".tar") return BagFormat::Tar;
  if (ext == ".zip") return BagFormat::Zip;
  return BagFormat::Directory;
}

const char* bagFormatName(BagFormat format) {
  switch (format) {
    case BagFormat::Tar: return "tar";
    case BagFormat::Zip: return "zip";
    default: return "directory";
  }
}

namespace {

// A write the system refused (`error`, an errno) is the environment's: exit 1 with what to do
// (core/atomic_file.h, writeError). Without an errno, the library failed on its own: a bug.
[[noreturn]] void throwWriteError(const fs::path& out, int error, const std::string& why = "") {
  if (error != 0) throw writeError(out, "packing", error);
  throw Error(ErrorKind::Internal, out.string(), "packing", "could not write the package (" + why + ")");
}
[[noreturn]] void throwWriteError(const fs::path& out, const std::error_code& ec) {
  throwWriteError(out, ec.value(), ec.message());
}

// Zip stores MS-DOS times in local time: pin the zone to UTC while writing, so the bytes do not
// depend on the machine's time zone.
class UtcZone {
 public:
  UtcZone() {
    if (const char* tz = std::getenv("TZ")) saved_ = tz;
    ::setenv("TZ", "UTC0", 1);
    ::tzset();
  }
  ~UtcZone() {
    if (saved_) ::setenv("TZ", saved_->c_str(), 1);
    else ::unsetenv("TZ");
    ::tzset();
  }

 private:
  std::optional<std::string> saved_;
};

// Entry names are UTF-8 whatever the user's locale: libarchive converts names through the
// thread's locale, so use a UTF-8 one on this thread while writing (uselocale is per thread).
class Utf8Locale {
 public:
  Utf8Locale() {
    for (const char* name : {"C.UTF-8", "C.utf8", "en_US.UTF-8"}) {
      locale_ = ::newlocale(LC_CTYPE_MASK, name, static_cast<locale_t>(0));
      if (locale_) break;
    }
    if (!locale_) {
      throw Error(ErrorKind::Internal, "C.UTF-8", "packing",
                  "no UTF-8 locale is installed, which archive file names need; install the "
                  "locales package");
    }
    previous_ = ::uselocale(locale_);
  }
  ~Utf8Locale() {
    ::uselocale(previous_);
    ::freelocale(locale_);
  }

 private:
  locale_t locale_ = static_cast<locale_t>(0);
  locale_t previous_ = static_cast<locale_t>(0);
};

class DirectorySink : public Sink {
 public:
  DirectorySink(fs::path root, fs::path shownAs, std::int64_t epoch)
      : root_(std::move(root)), shown_(std::move(shownAs)), epoch_(epoch) {
    std::error_code ec;
    fs::create_directories(root_, ec);
    if (ec) throwWriteError(shown_, ec);
  }
  ~DirectorySink() override {
    if (fd_ >= 0) ::close(fd_);
  }
  void begin(const std::string& bagPath, std::uint64_t) override {
    current_ = root_ / fs::u8path(bagPath);
    std::error_code ec;
    fs::create_directories(current_.parent_path(), ec);
    if (ec) throwWriteError(shown_, ec);
    fd_ = ::open(current_.c_str(), O_WRONLY | O_CREAT | O_EXCL | O_CLOEXEC, 0644);
    if (fd_ < 0) throwWriteError(shown_, errno);
    ::fchmod(fd_, 0644);  // not subject to the umask
  }
  void write(const void* data, std::size_t size) override {
    const char* p = static_cast<const char*>(data);
    while (size > 0) {
      const ssize_t n = ::write(fd_, p, size);
      if (n < 0) {
        if (errno == EINTR) continue;
        throwWriteError(shown_, errno);
      }
      p += n;
      size -= static_cast<std::size_t>(n);
    }
  }
  void end() override {
    const timespec times[2] = {{static_cast<time_t>(epoch_), 0}, {static_cast<time_t>(epoch_), 0}};
    ::futimens(fd_, times);
    const int rc = ::close(fd_);  // flushed once for all files in close()
    fd_ = -1;
    if (rc != 0) throwWriteError(shown_, errno);
  }
  void close() override {
    // Folders: fixed permissions and time too (deepest first, so setting a time sticks).
    std::vector<fs::path> dirs;
    for (auto it = fs::recursive_directory_iterator(root_); it != fs::recursive_directory_iterator(); ++it)
      if (it->is_directory()) dirs.push_back(it->path());
    dirs.push_back(root_);
    std::sort(dirs.begin(), dirs.end(), [](const fs::path& a, const fs::path& b) {
      return a.string().size() > b.string().size();
    });
    const timespec times[2] = {{static_cast<time_t>(epoch_), 0}, {static_cast<time_t>(epoch_), 0}};
    for (const fs::path& d : dirs) {
      ::chmod(d.c_str(), 0755);
      ::utimensat(AT_FDCWD, d.c_str(), times, 0);
    }
    // Everything on disk before the folder gets its final name (one syncfs rather than an
    // fsync per file: same guarantee, far fewer flushes).
    const int fd = ::open(root_.c_str(), O_RDONLY | O_DIRECTORY | O_CLOEXEC);
    if (fd < 0) throwWriteError(shown_, errno);
    const int rc = ::syncfs(fd);
    const int err = errno;
    ::close(fd);
    if (rc != 0) throwWriteError(shown_, err);
  }

 private:
  fs::path root_, shown_, current_;
  std::int64_t epoch_;
  int fd_ = -1;
};

class ArchiveSink : public Sink {
 public:
  ArchiveSink(const fs::path& file, const fs::path& shownAs, BagFormat format,
              std::string topFolder, std::int64_t epoch)
      : zone_(utcFor(format)), shown_(shownAs), top_(std::move(topFolder)), epoch_(epoch) {
    a_ = archive_write_new();
    if (!a_) throwWriteError(shown_, 0, "libarchive could not start");
    int rc;
    if (format == BagFormat::Zip) {
      rc = archive_write_set_format_zip(a_);
      // Payload images are compressed already: storing keeps packing at disk speed.
      if (rc == ARCHIVE_OK) rc = archive_write_zip_set_compression_store(a_);
      if (rc == ARCHIVE_OK) rc = archive_write_set_bytes_in_last_block(a_, 1);
    } else {
      // POSIX pax, with extended headers only where ustar cannot hold a name or size; the end
      // padded to the usual 10240-byte tar record.
      rc = archive_write_set_format_pax_restricted(a_);
      if (rc == ARCHIVE_OK) rc = archive_write_set_bytes_in_last_block(a_, 10240);
    }
    // Large output blocks: one write() per MiB rather than per 10 KiB.
    if (rc == ARCHIVE_OK) rc = archive_write_set_bytes_per_block(a_, 1 << 20);
    if (rc == ARCHIVE_OK) rc = archive_write_open_filename(a_, file.c_str());
    if (rc != ARCHIVE_OK) fail();
    entry_ = archive_entry_new();
  }
  ~ArchiveSink() override {
    if (entry_) archive_entry_free(entry_);
    if (a_) archive_write_free(a_);  // closes too when close() was not reached
  }
  void begin(const std::string& bagPath, std::uint64_t size) override {
    archive_entry_clear(entry_);
    const std::string name = top_ + "/" + bagPath;
    // libarchive keeps a name that is not UTF-8 without a word, then finds no name to write:
    // a null pointer in its zip writer (a crash), "no pathname" in its tar writer. The names
    // were judged before packing (checkPackageName, the capture's names): this is the guard.
    if (!isValidUtf8(name))
      throw Error(ErrorKind::Input, shownName(shown_.string()), "packing",
                  "cannot hold the entry \"" + shownName(name) + "\": a package's names are UTF-8");
    archive_entry_set_pathname_utf8(entry_, name.c_str());
    archive_entry_set_size(entry_, static_cast<la_int64_t>(size));
    archive_entry_set_filetype(entry_, AE_IFREG);
    archive_entry_set_perm(entry_, 0644);
    archive_entry_set_mtime(entry_, static_cast<time_t>(epoch_), 0);
    archive_entry_set_uid(entry_, 0);
    archive_entry_set_gid(entry_, 0);
    archive_entry_set_uname(entry_, "root");
    archive_entry_set_gname(entry_, "root");
    if (archive_write_header(a_, entry_) != ARCHIVE_OK) fail();
  }
  void write(const void* data, std::size_t size) override {
    const char* p = static_cast<const char*>(data);
    while (size > 0) {
      const la_ssize_t n = archive_write_data(a_, p, size);
      if (n <= 0) fail();
      p += n;
      size -= static_cast<std::size_t>(n);
    }
  }
  void end() override {
    if (archive_write_finish_entry(a_) != ARCHIVE_OK) fail();
  }
  void close() override {
    if (archive_write_close(a_) != ARCHIVE_OK) fail();
  }

 private:
  static std::optional<UtcZone> utcFor(BagFormat format) {
    if (format == BagFormat::Zip) return std::optional<UtcZone>(std::in_place);
    return std::nullopt;
  }
  [[noreturn]] void fail() {
    const char* why = a_ ? archive_error_string(a_) : nullptr;
    // libarchive's own failures carry ARCHIVE_ERRNO_MISC (-1) or other values that are no errno.
    const int err = a_ && archive_errno(a_) > 0 ? archive_errno(a_) : 0;
    throwWriteError(shown_, err, why ? why : "libarchive error");
  }
  // First, so that they hold from the archive's start to after it is freed.
  std::optional<UtcZone> zone_;
  Utf8Locale utf8_;
  ::archive* a_ = nullptr;
  ::archive_entry* entry_ = nullptr;
  fs::path shown_;
  std::string top_;
  std::int64_t epoch_;
};

}  // namespace

std::unique_ptr<Sink> openSink(BagFormat format, const fs::path& staging, const fs::path& out,
                               std::int64_t epoch) {
  if (format == BagFormat::Directory) return std::make_unique<DirectorySink>(staging, out, epoch);
  return std::make_unique<ArchiveSink>(staging, out, format, out.stem().string(), epoch);
}

std::vector<std::string> removeStaleParts(const fs::path& out) {
  std::vector<std::string> removed;
  for (const AbandonedTemporary& part : abandonedTemporaries(out)) {
    std::error_code rec;
    const fs::file_status status = fs::symlink_status(part.path, rec);
    // A partial folder bag may hold read-only folders (copied permissions, an interrupted
    // chmod): make them writable for their owner first, so that everything can go.
    if (fs::is_directory(status)) {
      for (fs::recursive_directory_iterator d(part.path, rec), dend; !rec && d != dend; d.increment(rec))
        if (d->is_directory(rec) && !d->is_symlink(rec))
          fs::permissions(d->path(), fs::perms::owner_all, fs::perm_options::add, rec);
      fs::permissions(part.path, fs::perms::owner_all, fs::perm_options::add, rec);
      rec.clear();
    }
    fs::remove_all(part.path, rec);
    if (rec) continue;
    removed.push_back("removed " + part.path.string() + ", the partial output of a pack that "
                      "did not finish (process " + std::to_string(part.pid) + " no longer runs)");
  }
  return removed;
}

void checkPackageName(const fs::path& out) {
  fs::path named = out.lexically_normal();
  if (named.filename().empty()) named = named.parent_path();  // "pkg/" is the folder pkg
  const std::string name = named.filename().string();
  std::string why = unholdableCharacters(name);
  // An E-ARK SIP's METS names it (OBJID): no character XML cannot hold (U+FFFE, U+FFFF), and
  // none a terminal shows only escaped (C1 controls), in any layout.
  if (why.empty() && needsEscaping(name))
    why = "contains a character XML cannot hold or a terminal cannot show (U+FFFE, U+FFFF, a C1 control)";
  if (why.empty() && bagFormatFor(named) != BagFormat::Directory) {
    // An archive holds its bag in a folder named after it: every entry's path begins with that
    // name, so it must be one verify reads as a path inside the package ("a:b" reads as a drive
    // letter, "~x" as a home folder, "." and ".." as no folder at all).
    const std::string top = named.stem().string();
    std::string entryWhy;
    if (!safeBagPath(top + "/bagit.txt", &entryWhy) || top == "." || top == "..")
      why = "leaves \"" + top + "\" as the name of the folder the archive holds its bag in (" +
            (entryWhy.empty() ? "no folder" : entryWhy) + ")";
  }
  if (!why.empty())
    throw Error(ErrorKind::Input, escapedText(out.string()), "packing",
                "cannot name a package: its name " + why + ", which a package cannot hold (verify "
                "would refuse it, and other systems could not unpack it); nothing was written: "
                "choose another name, of UTF-8 text without control characters or backslashes");
}

void checkOutput(const fs::path& out, bool replace) {
  checkPackageName(out);
  const BagFormat format = bagFormatFor(out);
  std::error_code ec;
  if (!replace && format != BagFormat::Directory && fs::exists(fs::symlink_status(out, ec))) {
    throw Error(ErrorKind::Input, shownName(out.string()), "packing",
                "already exists; pack never replaces a package silently: give --force to replace "
                "it, or choose another name");
  }
  // An output that exists is one the output rule forbids (exit 1), for a bag folder as for an
  // archive: two packs racing to one folder name then fail the same way whichever check sees it.
  if (format == BagFormat::Directory && fs::exists(out) &&
      !(fs::is_directory(out) && fs::is_empty(out))) {
    throw Error(ErrorKind::Input, shownName(out.string()), "packing",
                "already exists; remove it or choose another output name");
  }
  if (format != BagFormat::Directory && fs::is_directory(out)) {
    throw Error(ErrorKind::Usage, shownName(out.string()), "packing",
                "is a folder; choose a file name ending in .tar or .zip");
  }
  const fs::path parent = out.parent_path().empty() ? fs::path(".") : out.parent_path();
  if (!fs::is_directory(parent)) {
    throw Error(ErrorKind::Usage, shownName(out.string()), "packing",
                "cannot be written: the folder " + parent.string() + " does not exist");
  }
}

}  // namespace surrogate::archive
