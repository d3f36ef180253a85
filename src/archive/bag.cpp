#include "archive/bag.h"

#include <archive.h>
#include <archive_entry.h>
#include <fcntl.h>
#include <signal.h>
#include <sys/stat.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <chrono>
#include <condition_variable>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <ctime>
#include <locale.h>
#include <memory>
#include <mutex>
#include <set>
#include <thread>

#include "core/atomic_file.h"
#include "core/digest.h"
#include "core/error.h"
#include "core/text.h"

namespace surrogate::archive {

namespace fs = std::filesystem;

// ---------------------------------------------------------------------------------------------
// Small helpers

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
std::optional<std::int64_t> parseSourceDateEpoch() {
  const char* env = std::getenv("SOURCE_DATE_EPOCH");
  if (!env || !*env) return std::nullopt;
  char* end = nullptr;
  errno = 0;
  const long long value = std::strtoll(env, &end, 10);
  if (errno != 0 || *end != '\0' || value < 0) return std::nullopt;
  return static_cast<std::int64_t>(value);
}
}  // namespace

std::int64_t sourceDateEpoch() { return parseSourceDateEpoch().value_or(kDefaultEpoch); }
bool sourceDateEpochSet() { return parseSourceDateEpoch().has_value(); }
std::int64_t packagingEpoch() {
  if (auto e = parseSourceDateEpoch()) return *e;
  return static_cast<std::int64_t>(std::time(nullptr));
}

std::string escapeManifestPath(const std::string& path) {
  std::string out;
  out.reserve(path.size());
  for (const char c : path) {
    if (c == '%') out += "%25";
    else if (c == '\r') out += "%0D";
    else if (c == '\n') out += "%0A";
    else out.push_back(c);
  }
  return out;
}

std::string humanSize(std::uint64_t bytes) {
  if (bytes < 1000) return std::to_string(bytes) + " bytes";
  static const char* units[] = {"KB", "MB", "GB", "TB", "PB", "EB"};
  double value = static_cast<double>(bytes);
  int unit = -1;
  while (value >= 1000 && unit < 5) {
    value /= 1000;
    ++unit;
  }
  char text[32];
  std::snprintf(text, sizeof text, "%.1f %s", value, units[unit]);
  return text;
}

namespace {
std::tm utc(std::int64_t epoch) {
  const std::time_t t = static_cast<std::time_t>(epoch);
  std::tm tm{};
  gmtime_r(&t, &tm);
  return tm;
}
}  // namespace

std::string utcDate(std::int64_t epoch) {
  const std::tm tm = utc(epoch);
  char text[16];
  std::strftime(text, sizeof text, "%Y-%m-%d", &tm);
  return text;
}

std::string utcDateTime(std::int64_t epoch) {
  const std::tm tm = utc(epoch);
  char text[32];
  std::strftime(text, sizeof text, "%Y-%m-%dT%H:%M:%SZ", &tm);
  return text;
}

namespace {
std::string labelFormProblem(const std::string& label) {
  const bool bad = label.empty() || std::any_of(label.begin(), label.end(), [](unsigned char c) {
                     return c == ':' || c <= ' ' || c == 0x7f;
                   });
  if (bad)
    return "is not a usable bag-info.txt label (no spaces, colons or control characters); "
           "rename the metadata key, e.g. Source-Organization";
  return "";
}
}  // namespace

std::string bagInfoLabelProblem(const std::string& label) {
  static const std::set<std::string> computed = {"payload-oxum", "bagging-date", "bag-size",
                                                  "bag-software-agent"};
  static const std::set<std::string> own = {"surrogate-package-identifier",
                                             "surrogate-packaging-time"};
  if (computed.count(lowerCase(label)))
    return "is computed by Surrogate for bag-info.txt and cannot be given as metadata; "
           "remove it from the capture's metadata (--meta)";
  if (own.count(lowerCase(label)))
    return "is written by `surrogate pack` itself (the package's identifier, the SHA-256 of its "
           "carrier, and the packaging time) and cannot be given as metadata; remove it from the "
           "capture's metadata (--meta)";
  return labelFormProblem(label);
}

namespace {

constexpr std::size_t kBufferSize = 1 << 20;

// ---------------------------------------------------------------------------------------------
// Where entries go: a folder, or a libarchive writer.

class Sink {
 public:
  virtual ~Sink() = default;
  virtual void begin(const std::string& bagPath, std::uint64_t size) = 0;
  virtual void write(const void* data, std::size_t size) = 0;
  virtual void end() = 0;
  virtual void close() = 0;
};

// A write the system refused (`error`, an errno) is the environment's: exit 1 with what to do
// (core/atomic_file.h, writeError). Without an errno, the library failed on its own: a bug.
[[noreturn]] void throwWriteError(const fs::path& out, int error, const std::string& why = "") {
  if (error != 0) throw writeError(out, "packing", error);
  throw Error(ErrorKind::Internal, out.string(), "packing", "could not write the package (" + why + ")");
}
[[noreturn]] void throwWriteError(const fs::path& out, const std::error_code& ec) {
  throwWriteError(out, ec.value(), ec.message());
}

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
      : shown_(shownAs), top_(std::move(topFolder)), epoch_(epoch) {
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
  [[noreturn]] void fail() {
    const char* why = a_ ? archive_error_string(a_) : nullptr;
    const int err = a_ ? archive_errno(a_) : 0;
    throwWriteError(shown_, err, why ? why : "libarchive error");
  }
  ::archive* a_ = nullptr;
  ::archive_entry* entry_ = nullptr;
  fs::path shown_;
  std::string top_;
  std::int64_t epoch_;
};

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

// ---------------------------------------------------------------------------------------------
// Checks of the inputs

bool safeRelative(const std::string& path) {
  if (path.empty() || path.front() == '/' || path.back() == '/') return false;
  if (path.find('\0') != std::string::npos) return false;
  std::size_t start = 0;
  while (start <= path.size()) {
    std::size_t slash = path.find('/', start);
    if (slash == std::string::npos) slash = path.size();
    const std::string segment = path.substr(start, slash - start);
    if (segment.empty() || segment == "." || segment == "..") return false;
    start = slash + 1;
  }
  return true;
}

void checkLabel(const std::string& label) {
  const std::string problem = bagInfoLabelProblem(label);
  if (!problem.empty()) throw Error(ErrorKind::Usage, label, "packing", problem);
}

// "Label: value", with line breaks in the value folded into continuation lines.
std::string infoLine(const std::string& label, const std::string& value) {
  std::string line = label + ": ";
  for (std::size_t i = 0; i < value.size(); ++i) {
    const char c = value[i];
    if (c == '\r' && i + 1 < value.size() && value[i + 1] == '\n') continue;
    if (c == '\n' || c == '\r') line += "\n  ";
    else line.push_back(c);
  }
  return line + "\n";
}

std::string manifestText(const std::vector<PayloadDigest>& items, DigestAlgorithm algorithm) {
  std::string text;
  for (const PayloadDigest& d : items) {
    text += (algorithm == DigestAlgorithm::Sha256 ? d.sha256 : d.sha512);
    text += "  ";
    text += escapeManifestPath(d.bagPath);
    text += "\n";
  }
  return text;
}

PayloadDigest digestOf(const std::string& bagPath, const std::string& content) {
  MultiDigest d({DigestAlgorithm::Sha256, DigestAlgorithm::Sha512});
  d.update(content.data(), content.size());
  return {bagPath, content.size(), d.hex(DigestAlgorithm::Sha256), d.hex(DigestAlgorithm::Sha512)};
}

// One digest computed on its own thread, chunk by chunk: SHA-256 and SHA-512 of the same
// buffer run side by side (and beside the write), so packing costs about one SHA-512 pass.
class DigestWorker {
 public:
  explicit DigestWorker(DigestAlgorithm algorithm) : digest_({algorithm}), thread_([this] { loop(); }) {}
  ~DigestWorker() {
    {
      std::lock_guard<std::mutex> lock(mutex_);
      stop_ = true;
    }
    wake_.notify_all();
    thread_.join();
  }
  DigestWorker(const DigestWorker&) = delete;
  DigestWorker& operator=(const DigestWorker&) = delete;

  // Starts hashing `size` bytes at `data`; the buffer must stay untouched until wait().
  void submit(const void* data, std::size_t size) {
    {
      std::lock_guard<std::mutex> lock(mutex_);
      data_ = data;
      size_ = size;
      busy_ = true;
    }
    wake_.notify_all();
  }
  void wait() {
    std::unique_lock<std::mutex> lock(mutex_);
    done_.wait(lock, [this] { return !busy_; });
  }
  // Finishes (after wait()) and returns the hex digest; starts a new one for the next file.
  std::string finish(DigestAlgorithm algorithm) {
    wait();
    std::string hex = digest_.hex(algorithm);
    digest_ = MultiDigest({algorithm});
    return hex;
  }

 private:
  void loop() {
    std::unique_lock<std::mutex> lock(mutex_);
    for (;;) {
      wake_.wait(lock, [this] { return stop_ || busy_; });
      if (stop_) return;
      const void* data = data_;
      const std::size_t size = size_;
      lock.unlock();
      digest_.update(data, size);
      lock.lock();
      busy_ = false;
      done_.notify_all();
    }
  }

  MultiDigest digest_;
  std::mutex mutex_;
  std::condition_variable wake_, done_;
  const void* data_ = nullptr;
  std::size_t size_ = 0;
  bool busy_ = false, stop_ = false;
  std::thread thread_;
};

// Both digests of a stream: on two worker threads when the machine has two cores or more,
// else in this thread.
class PayloadHasher {
 public:
  PayloadHasher() {
    if (std::thread::hardware_concurrency() >= 2) {
      sha256_ = std::make_unique<DigestWorker>(DigestAlgorithm::Sha256);
      sha512_ = std::make_unique<DigestWorker>(DigestAlgorithm::Sha512);
    }
  }
  bool parallel() const { return sha256_ != nullptr; }
  // Parallel: starts hashing (the buffer must stay untouched until wait()). Else: hashes now.
  void submit(const void* data, std::size_t size) {
    if (parallel()) {
      sha256_->submit(data, size);
      sha512_->submit(data, size);
    } else {
      serial_.update(data, size);
    }
  }
  void wait() {
    if (parallel()) {
      sha256_->wait();
      sha512_->wait();
    }
  }
  std::pair<std::string, std::string> finish() {
    if (parallel()) return {sha256_->finish(DigestAlgorithm::Sha256), sha512_->finish(DigestAlgorithm::Sha512)};
    std::pair<std::string, std::string> out{serial_.hex(DigestAlgorithm::Sha256), serial_.hex(DigestAlgorithm::Sha512)};
    serial_ = MultiDigest({DigestAlgorithm::Sha256, DigestAlgorithm::Sha512});
    return out;
  }

 private:
  std::unique_ptr<DigestWorker> sha256_, sha512_;
  MultiDigest serial_{{DigestAlgorithm::Sha256, DigestAlgorithm::Sha512}};
};

struct Source {
  const PayloadSource* in;
  std::uint64_t size;
};

// Streams one payload file into the sink, hashing the same buffer. Returns its digests.
// Two buffers alternate: while the digests of one run, the other is being read.
PayloadDigest streamFile(const Source& src, Sink& sink, PayloadHasher& hasher,
                         std::vector<unsigned char> (&buffers)[2],
                         const std::function<void(std::uint64_t)>& advance) {
  const std::string shown = src.in->source.string();
  const int fd = ::open(src.in->source.c_str(), O_RDONLY | O_CLOEXEC | O_NOFOLLOW);
  if (fd < 0) {
    throwInputError(shown, "packing",
                    std::string("cannot be read (") + std::strerror(errno) +
                        "); check its permissions, or copy it again from the card");
  }
  ::posix_fadvise(fd, 0, 0, POSIX_FADV_SEQUENTIAL);
  struct Closer {
    int fd;
    PayloadHasher& hasher;
    ~Closer() {
      hasher.wait();  // never leave a worker reading a buffer on the way out
      ::close(fd);
    }
  } closer{fd, hasher};
  sink.begin(src.in->bagPath, src.size);
  std::uint64_t done = 0;
  int current = 0;
  for (;;) {
    std::vector<unsigned char>& buffer = buffers[current];
    ssize_t n;
    do {
      n = ::read(fd, buffer.data(), buffer.size());
    } while (n < 0 && errno == EINTR);
    if (n < 0) {
      throwInputError(shown, "packing",
                      std::string("reading failed (") + std::strerror(errno) +
                          "); the disk or card may be failing: copy the file again");
    }
    if (n == 0) break;
    if (done + static_cast<std::uint64_t>(n) > src.size) {  // grew: reported below
      done += static_cast<std::uint64_t>(n);
      break;
    }
    hasher.wait();  // the previous chunk's digests are done: its buffer may be reused next
    hasher.submit(buffer.data(), static_cast<std::size_t>(n));
    sink.write(buffer.data(), static_cast<std::size_t>(n));
    done += static_cast<std::uint64_t>(n);
    advance(static_cast<std::uint64_t>(n));
    current = 1 - current;
  }
  hasher.wait();
  if (done != src.size) {
    hasher.finish();  // discard
    throwInputError(shown, "packing",
                    "changed size while it was being packed; make sure nothing writes to the "
                    "capture, then pack again");
  }
  sink.end();
  const auto [sha256, sha512] = hasher.finish();
  PayloadDigest out{src.in->bagPath, done, sha256, sha512};
  if (!src.in->expectedSha256.empty() && src.in->expectedSha256 != out.sha256)
    throw PayloadChanged(src.in->bagPath, shown);
  return out;
}

// The payload: checked, sorted by bag path, sized (lstat: a symbolic link is refused, never
// followed); `total` receives the sum of the sizes.
std::vector<Source> checkedPayload(const BagInput& input, std::uint64_t& total) {
  std::vector<Source> sources;
  std::set<std::string> seen;
  total = 0;
  for (const PayloadSource& p : input.payload) {
    if (p.bagPath.rfind("data/", 0) != 0 || !safeRelative(p.bagPath)) {
      throw Error(ErrorKind::Internal, p.bagPath, "packing",
                  "is not a valid payload path (must be under data/, without '..')");
    }
    if (!seen.insert(p.bagPath).second) {
      throw Error(ErrorKind::Internal, p.bagPath, "packing", "is listed twice in the payload");
    }
    struct stat st {};
    if (::lstat(p.source.c_str(), &st) != 0) {
      throwInputError(p.source.string(), "packing",
                      std::string("cannot be read (") + std::strerror(errno) +
                          "); it is listed in the capture but missing or inaccessible");
    }
    if (!S_ISREG(st.st_mode)) {
      throwInputError(p.source.string(), "packing",
                      "is not a regular file (a link, folder or device); replace it with the "
                      "file itself");
    }
    sources.push_back({&p, static_cast<std::uint64_t>(st.st_size)});
    total += static_cast<std::uint64_t>(st.st_size);
  }
  std::sort(sources.begin(), sources.end(),
            [](const Source& a, const Source& b) { return a.in->bagPath < b.in->bagPath; });
  return sources;
}

// bag-info.txt: the computed labels, then the caller's, then the caller's own (checked).
std::string bagInfoText(const BagInput& input, std::uint64_t total, std::size_t files) {
  const std::string baggingDate =
      input.baggingDate.empty() ? utcDate(packagingEpoch()) : input.baggingDate;
  std::string info;
  info += infoLine("Bag-Software-Agent", input.softwareAgent);
  info += infoLine("Bagging-Date", baggingDate);
  info += infoLine("Bag-Size", humanSize(total));
  info += infoLine("Payload-Oxum", std::to_string(total) + "." + std::to_string(files));
  for (const auto& [label, value] : input.info) {
    checkLabel(label);
    info += infoLine(label, value);
  }
  for (const auto& [label, value] : input.ownInfo) {
    if (const std::string problem = labelFormProblem(label); !problem.empty())
      throw Error(ErrorKind::Internal, label, "packing", problem);
    info += infoLine(label, value);
  }
  return info;
}

std::unique_ptr<Sink> openSink(BagFormat format, const AtomicFile& target, const fs::path& out,
                               std::int64_t epoch) {
  if (format == BagFormat::Directory)
    return std::make_unique<DirectorySink>(target.tempPath(), out, epoch);
  return std::make_unique<ArchiveSink>(target.tempPath(), out, format, out.stem().string(), epoch);
}

// Every payload file into the sink, in order, with its digests.
std::vector<PayloadDigest> streamPayload(const BagInput& input, const std::vector<Source>& sources,
                                         std::uint64_t total, Sink& sink) {
  std::vector<unsigned char> buffers[2] = {std::vector<unsigned char>(kBufferSize),
                                           std::vector<unsigned char>(kBufferSize)};
  PayloadHasher hasher;
  std::uint64_t done = 0;
  auto advance = [&](std::uint64_t n) {
    done += n;
    if (input.progress) input.progress(done, total);
  };
  std::vector<PayloadDigest> digests;
  digests.reserve(sources.size());
  for (const Source& s : sources) digests.push_back(streamFile(s, sink, hasher, buffers, advance));
  return digests;
}

// The manifests and the caller's tag files (checked: no reserved name, nothing in data/, no
// duplicate), in path order.
std::vector<TagFile> sortedTagFiles(const BagInput& input, const std::vector<PayloadDigest>& payload) {
  std::vector<TagFile> tags;
  tags.push_back({"manifest-sha256.txt", manifestText(payload, DigestAlgorithm::Sha256), {}});
  tags.push_back({"manifest-sha512.txt", manifestText(payload, DigestAlgorithm::Sha512), {}});
  if (input.tagFiles) {
    for (TagFile& t : input.tagFiles(payload)) {
      const bool reserved = t.bagPath == "bagit.txt" || t.bagPath == "bag-info.txt" ||
                            t.bagPath.rfind("manifest-", 0) == 0 ||
                            t.bagPath.rfind("tagmanifest-", 0) == 0 || t.bagPath == "fetch.txt";
      if (!safeRelative(t.bagPath) || t.bagPath.rfind("data/", 0) == 0 || reserved) {
        throw Error(ErrorKind::Internal, t.bagPath, "packing", "is not a valid tag file path");
      }
      tags.push_back(std::move(t));
    }
  }
  std::sort(tags.begin(), tags.end(),
            [](const TagFile& a, const TagFile& b) { return a.bagPath < b.bagPath; });
  for (std::size_t i = 1; i < tags.size(); ++i) {
    if (tags[i].bagPath == tags[i - 1].bagPath)
      throw Error(ErrorKind::Internal, tags[i].bagPath, "packing", "is given twice");
  }
  return tags;
}

}  // namespace

std::vector<std::string> removeStaleParts(const fs::path& out) {
  // AtomicFile's temporary name: ".NAME.part-PID-N" in the same folder.
  const std::string prefix = "." + out.filename().string() + ".part-";
  const fs::path folder = out.parent_path().empty() ? fs::path(".") : out.parent_path();
  std::vector<std::string> removed;
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
    // Alive (or not ours to signal): keep it. Only "no such process" means it is gone.
    if (pid <= 0 || pid == ::getpid() || ::kill(pid, 0) == 0 || errno != ESRCH) continue;
    std::error_code rec;
    // A partial folder bag may hold read-only folders (copied permissions, an interrupted
    // chmod): make them writable for their owner first, so that everything can go.
    if (it->is_directory(rec) && !it->is_symlink(rec)) {
      for (fs::recursive_directory_iterator d(it->path(), rec), dend; !rec && d != dend; d.increment(rec))
        if (d->is_directory(rec) && !d->is_symlink(rec))
          fs::permissions(d->path(), fs::perms::owner_all, fs::perm_options::add, rec);
      fs::permissions(it->path(), fs::perms::owner_all, fs::perm_options::add, rec);
      rec.clear();
    }
    fs::remove_all(it->path(), rec);
    if (rec) continue;
    removed.push_back("removed " + it->path().string() + ", the partial output of a pack that "
                      "did not finish (process " + std::to_string(pid) + " no longer runs)");
  }
  return removed;
}

void checkOutput(const fs::path& out, bool replace) {
  const BagFormat format = bagFormatFor(out);
  std::error_code ec;
  if (!replace && format != BagFormat::Directory && fs::exists(fs::symlink_status(out, ec))) {
    throw Error(ErrorKind::Input, out.string(), "packing",
                "already exists; pack never replaces a package silently: give --force to replace "
                "it, or choose another name");
  }
  if (format == BagFormat::Directory && fs::exists(out) &&
      !(fs::is_directory(out) && fs::is_empty(out))) {
    throw Error(ErrorKind::Usage, out.string(), "packing",
                "already exists; remove it or choose another output name");
  }
  if (format != BagFormat::Directory && fs::is_directory(out)) {
    throw Error(ErrorKind::Usage, out.string(), "packing",
                "is a folder; choose a file name ending in .tar or .zip");
  }
  const fs::path parent = out.parent_path().empty() ? fs::path(".") : out.parent_path();
  if (!fs::is_directory(parent)) {
    throw Error(ErrorKind::Usage, out.string(), "packing",
                "cannot be written: the folder " + parent.string() + " does not exist");
  }
}

BagResult writeBag(const BagInput& input, const fs::path& out) {
  const auto started = std::chrono::steady_clock::now();
  const BagFormat format = bagFormatFor(out);
  const std::int64_t epoch = input.epoch.value_or(sourceDateEpoch());

  std::uint64_t total = 0;
  const std::vector<Source> sources = checkedPayload(input, total);
  // bag-info.txt and bagit.txt need only the sizes: they come first, as the sorted order wants.
  const std::string info = bagInfoText(input, total, sources.size());
  const std::string bagit = "BagIt-Version: 1.0\nTag-File-Character-Encoding: UTF-8\n";

  // The output, under a temporary name until complete; first the partial outputs of packs to
  // the same name that were killed.
  checkOutput(out, input.replace);
  std::vector<std::string> removedLeftovers = removeStaleParts(out);
  AtomicFile target(out);
  std::optional<UtcZone> zone;
  if (format == BagFormat::Zip) zone.emplace();
  std::optional<Utf8Locale> utf8;
  if (format != BagFormat::Directory) utf8.emplace();
  std::unique_ptr<Sink> sink = openSink(format, target, out, epoch);

  std::vector<PayloadDigest> tagDigests;
  auto putTag = [&](const std::string& path, const std::string& content, bool listed) {
    sink->begin(path, content.size());
    sink->write(content.data(), content.size());
    sink->end();
    if (listed) tagDigests.push_back(digestOf(path, content));
  };
  putTag("bag-info.txt", info, true);
  putTag("bagit.txt", bagit, true);

  BagResult result;
  result.path = out;
  result.format = format;
  result.removedLeftovers = std::move(removedLeftovers);
  result.payloadBytes = total;
  result.payloadFiles = sources.size();
  result.payload = streamPayload(input, sources, total, *sink);

  // Manifests and the caller's tag files, in path order; then the tag manifests.
  for (const TagFile& t : sortedTagFiles(input, result.payload)) {
    if (t.file.empty()) {
      putTag(t.bagPath, t.content, true);
      continue;
    }
    std::unique_ptr<std::FILE, int (*)(std::FILE*)> in(std::fopen(t.file.c_str(), "rb"), &std::fclose);
    std::error_code ec;
    const std::uint64_t size = fs::file_size(t.file, ec);
    if (!in || ec)
      throw Error(ErrorKind::Internal, t.file.string(), "packing", "cannot read a derived tag file");
    MultiDigest digest({DigestAlgorithm::Sha256, DigestAlgorithm::Sha512});
    std::vector<char> buffer(kBufferSize);
    sink->begin(t.bagPath, size);
    std::uint64_t copied = 0;
    for (std::size_t n; (n = std::fread(buffer.data(), 1, buffer.size(), in.get())) > 0; copied += n) {
      sink->write(buffer.data(), n);
      digest.update(buffer.data(), n);
    }
    if (std::ferror(in.get()) || copied != size)
      throw Error(ErrorKind::Internal, t.file.string(), "packing", "cannot read a derived tag file");
    sink->end();
    tagDigests.push_back({t.bagPath, size, digest.hex(DigestAlgorithm::Sha256),
                          digest.hex(DigestAlgorithm::Sha512)});
  }
  std::sort(tagDigests.begin(), tagDigests.end(),
            [](const PayloadDigest& a, const PayloadDigest& b) { return a.bagPath < b.bagPath; });
  for (const PayloadDigest& d : tagDigests) result.tagFiles.push_back(d.bagPath);
  putTag("tagmanifest-sha256.txt", manifestText(tagDigests, DigestAlgorithm::Sha256), false);
  putTag("tagmanifest-sha512.txt", manifestText(tagDigests, DigestAlgorithm::Sha512), false);
  result.tagFiles.push_back("tagmanifest-sha256.txt");
  result.tagFiles.push_back("tagmanifest-sha512.txt");
  sink->close();
  sink.reset();
  if (input.replace)
    target.commit();
  else
    target.commitWithoutReplacing();
  result.seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - started).count();
  return result;
}

}  // namespace surrogate::archive
