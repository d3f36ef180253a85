// Private to src/archive: the checks the package reader makes on every entry, whatever its
// container (entry_checks.cpp): names, types, duplicates, size limits and decompression bombs,
// and the errors that refuse a package.
#pragma once

#include <cstddef>
#include <cstdint>
#include <functional>
#include <map>
#include <string>
#include <utility>

#include "archive/package_reader.h"
#include "archive/package_source.h"

namespace surrogate::archive {

// The step every error of the reader names.
inline constexpr const char* kStep = "verify";

// A hostile or malformed package: Error(Usage), nothing extracted.
[[noreturn]] void refuse(const std::string& where, const std::string& why);
// A truncated or damaged archive: Error(Fixity).
[[noreturn]] void damaged(const std::string& where, const std::string& why);
// Data after the end of an archive, covered by no manifest: Error(Fixity).
[[noreturn]] void trailing(const std::string& where, const std::string& why);

// Checks an entry's name (bag_text.h's safeBagPath) and type (regular files and folders
// only) and returns the normalised path; refuses the package `package` otherwise.
std::string checkedEntry(const RawEntry& entry, const std::string& package, const Limits& limits);

// The names of one package's entries, as the inventory is made: refuses two names that differ
// only in letter case or Unicode normalisation (they would overwrite each other on Windows or
// macOS), a file given twice, and a name that is a file and a folder at once.
class EntryNames {
 public:
  explicit EntryNames(std::string package) : package_(std::move(package)) {}
  // Before `path` (checked) joins `read`'s files, or its directories when `directory`.
  void add(const std::string& path, bool directory, const Inventory& read);
  // Once every entry is read: no file is also the folder of others ("a" and "a/b").
  void checkFilesAreNotFolders(const Inventory& read) const;

 private:
  std::string package_;
  std::map<std::string, std::string> folded_;  // case-fold key -> path
};

// Reads the current entry's content into `sink` piece by piece, enforcing the limits: no more
// bytes than its header declares, Limits::maxEntryBytes in one file, Limits::maxTotalBytes in
// all (`total` counts the package's bytes so far), and an archive expanding no more than
// Limits::maxRatio times. Returns the entry's size.
std::uint64_t pump(PackageSource& source, const RawEntry& entry, const std::string& path,
                   const Limits& limits, std::uint64_t& total,
                   const std::function<void(const char*, std::size_t)>& sink);

}  // namespace surrogate::archive
