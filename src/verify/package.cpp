#include "verify/package.h"

#include <archive.h>
#include <archive_entry.h>
#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <cstring>
#include <memory>
#include <vector>

#include "archive/digest.h"
#include "core/error.h"
#include "verify/bag_text.h"

namespace fs = std::filesystem;

namespace surrogate::verify {

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

// A .tar (optionally compressed) or .zip, streamed through libarchive.
class ArchiveSource : public Source {
 public:
  explicit ArchiveSource(const fs::path& file) : file_(file) {
    std::error_code ec;
    fileSize_ = fs::file_size(file, ec);
    a_.reset(archive_read_new());
    if (!a_) throw Error(ErrorKind::Internal, file.string(), kStep, "libarchive could not start");
    archive_read_support_filter_all(a_.get());
    archive_read_support_format_tar(a_.get());
    archive_read_support_format_gnutar(a_.get());
    archive_read_support_format_zip(a_.get());
    if (archive_read_open_filename(a_.get(), file.c_str(), 64 * 1024) != ARCHIVE_OK)
      notAPackage(archive_error_string(a_.get()));
  }

  bool next(RawEntry& entry) override {
    archive_entry* e = nullptr;
    const int r = archive_read_next_header(a_.get(), &e);
    if (r == ARCHIVE_EOF) return false;
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
  struct Free {
    void operator()(::archive* a) const { archive_read_free(a); }
  };
  // Owned from the start, so a constructor that throws (not a package) frees it too.
  std::unique_ptr<::archive, Free> a_;
  std::uint64_t fileSize_ = 0;
  bool first_ = true;
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

bool keepContent(const std::string& path) {
  const std::size_t slash = path.find('/');
  const std::string first = path.substr(0, slash);
  std::string second;
  if (slash != std::string::npos) second = path.substr(slash + 1, path.find('/', slash + 1) - slash - 1);
  const bool payload = first == "data" || second == "data";
  if (!payload) return true;
  const std::string carrier = "data/assembly-files/carrier.xml";
  return path.size() >= carrier.size() &&
         path.compare(path.size() - carrier.size(), carrier.size(), carrier) == 0;
}

// Reads one entry's content, enforcing the size limits; feeds `sink`.
template <typename Sink>
std::uint64_t pump(Source& source, const RawEntry& entry, const std::string& path,
                   const Limits& limits, std::uint64_t& total, Sink&& sink) {
  std::vector<char> buffer(256 * 1024);
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

Inventory readPackage(const fs::path& package, const Limits& limits, const Progress& progress) {
  std::unique_ptr<Source> source = openSource(package);
  const std::string name = package.string();
  Inventory raw;
  std::map<std::string, std::string> folded;  // case-fold key -> path
  std::uint64_t entries = 0, total = 0, kept = 0;
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
    archive::MultiDigest digest({archive::DigestAlgorithm::Sha256, archive::DigestAlgorithm::Sha512});
    const bool keep = keepContent(path);
    std::string content;
    file.size = pump(*source, entry, path, limits, total, [&](const char* data, std::size_t n) {
      digest.update(data, n);
      if (keep && content.size() <= limits.maxTagFileBytes) content.append(data, n);
    });
    file.sha256 = digest.hex(archive::DigestAlgorithm::Sha256);
    file.sha512 = digest.hex(archive::DigestAlgorithm::Sha512);
    if (keep && content.size() <= limits.maxTagFileBytes) {
      kept += content.size();
      if (kept > kMaxKeptBytes)
        refuse(name, "the package's tag files are larger than " +
                         std::to_string(kMaxKeptBytes) + " bytes in all");
      file.content = std::move(content);
    }
    raw.files.emplace(path, std::move(file));
    if (progress) progress("reading " + package.filename().string(), source->fraction());
  }
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
    archive::MultiDigest digest({archive::DigestAlgorithm::Sha256});
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
    if (digest.hex(archive::DigestAlgorithm::Sha256) != known->second.sha256)
      throw Error(ErrorKind::Fixity, path, kStep,
                  "the file changed between two reads of the package; is something writing to it?");
    if (progress) progress("extracting for re-execution", source->fraction());
  }
}

}  // namespace surrogate::verify
