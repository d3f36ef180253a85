// The checks the package reader makes on every entry of a bag directory, .tar or .zip alike,
// before anything else happens: its name and type, duplicates and names that collide once
// case is folded, and the limits on sizes and compression ratio (decompression bombs). Apart
// from the containers (directory_source.cpp, archive_source.cpp), so that the rules a hostile
// package meets are the same, in one place, whatever holds it.
#include "archive/entry_checks.h"

#include <utility>
#include <vector>

#include "archive/bag_text.h"
#include "core/error.h"
#include "core/file_names.h"

namespace surrogate::archive {

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

void EntryNames::add(const std::string& path, bool directory, const Inventory& read) {
  const auto [it, fresh] = folded_.emplace(caseFoldKey(path), path);
  if (!fresh && it->second != path)
    refuse(package_, "entries \"" + it->second + "\" and \"" + path +
                         "\" differ only in letter case or Unicode normalisation and would "
                         "overwrite each other on Windows or macOS");
  if (directory) {
    if (read.files.count(path)) refuse(package_, "\"" + path + "\" is both a file and a folder");
    return;
  }
  if (!fresh || read.files.count(path) || read.directories.count(path))
    refuse(package_, "entry \"" + path + "\" appears twice; a later copy could silently replace "
                     "the first");
}

void EntryNames::checkFilesAreNotFolders(const Inventory& read) const {
  for (const auto& [path, file] : read.files) {
    for (std::size_t slash = path.find('/'); slash != std::string::npos;
         slash = path.find('/', slash + 1))
      if (read.files.count(path.substr(0, slash)))
        refuse(package_, "\"" + path.substr(0, slash) + "\" is both a file and a folder");
  }
}

std::uint64_t pump(PackageSource& source, const RawEntry& entry, const std::string& path,
                   const Limits& limits, std::uint64_t& total,
                   const std::function<void(const char*, std::size_t)>& sink) {
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

}  // namespace surrogate::archive
