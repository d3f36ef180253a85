// Reading a package: the inventory (every file hashed, the small tag files kept), one file read
// again, and files extracted for re-execution and the report. What holds the entries is a
// PackageSource (package_source.h: a bag directory or an archive), and every entry meets the
// same checks (entry_checks.h) before anything else happens, so these three readings are
// written once for all containers.
#include "archive/package_reader.h"

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>
#include <iterator>
#include <memory>
#include <vector>

#include "archive/bag_text.h"
#include "archive/entry_checks.h"
#include "archive/package_source.h"
#include "core/digest.h"
#include "core/error.h"

namespace fs = std::filesystem;

namespace surrogate::archive {

namespace {

constexpr std::uint64_t kMaxKeptBytes = 512ull << 20;  // all tag files held in memory

std::unique_ptr<PackageSource> openSource(const fs::path& package) {
  std::error_code ec;
  const auto st = fs::symlink_status(package, ec);
  if (ec || !fs::exists(st))
    throw Error(ErrorKind::Input, package.string(), kStep,
                "does not exist; give a bag directory, .tar or .zip");
  if (fs::is_directory(fs::status(package, ec))) return openDirectorySource(package);
  if (!fs::is_regular_file(fs::status(package, ec)))
    throw Error(ErrorKind::Usage, package.string(), kStep,
                "is not a directory or a regular file; give a bag directory, .tar or .zip");
  return openArchiveSource(package);
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

}  // namespace

Inventory readPackage(const fs::path& package, const Limits& limits, const Progress& progress,
                      const std::vector<std::string>& otherDigests) {
  std::vector<std::string> algorithms = {"sha256", "sha512"};
  for (const std::string& name : otherDigests)
    if (name != "sha256" && name != "sha512") algorithms.push_back(name);
  std::unique_ptr<PackageSource> source = openSource(package);
  const std::string name = package.string();
  Inventory raw;
  EntryNames names(name);
  std::uint64_t entries = 0, total = 0, kept = 0;
  const std::string label = "reading " + package.filename().string();
  RawEntry entry;
  while (source->next(entry)) {
    if (++entries > limits.maxEntries)
      refuse(name, "the package has more than " + std::to_string(limits.maxEntries) + " entries");
    const std::string path = checkedEntry(entry, name, limits);
    names.add(path, entry.type == EntryType::Directory, raw);
    if (entry.type == EntryType::Directory) {
      raw.directories.insert(path);
      continue;
    }
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
    for (std::size_t i = 2; i < algorithms.size(); ++i)
      file.otherDigests[algorithms[i]] = digest.hex(algorithms[i]);
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
  names.checkFilesAreNotFolders(raw);

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
  std::unique_ptr<PackageSource> source = openSource(package);
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
  std::unique_ptr<PackageSource> source = openSource(package);
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
