// Private to src/archive: the entries of a package as its reader (package_reader.cpp) sees them,
// whatever holds them: a bag directory (directory_source.cpp), or a .tar or .zip streamed
// through libarchive (archive_source.cpp).
#pragma once

#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <memory>
#include <optional>
#include <string>

namespace surrogate::archive {

enum class EntryType { File, Directory, Symlink, Hardlink, Other };

// An entry as the container names it, before any check (entry_checks.h).
struct RawEntry {
  std::string path;
  EntryType type = EntryType::Other;
  std::string typeName;                      // "a symbolic link", "a FIFO", ... for the refusal
  std::optional<std::uint64_t> declaredSize;  // what the header or the file system says
};

// The entries of one package, read once in order.
class PackageSource {
 public:
  virtual ~PackageSource() = default;
  // The next entry, false after the last (when an archive is checked whole: archive_end.h).
  virtual bool next(RawEntry& entry) = 0;
  // Reads the current entry's content; 0 at its end.
  virtual std::size_t read(char* buffer, std::size_t size) = 0;
  virtual double fraction() const = 0;
  virtual std::uint64_t compressedBytes() const = 0;  // 0: not an archive
  std::string kind;  // "directory", "tar", "zip" (libarchive's format name otherwise)
};

// A bag directory: walked without following links, sorted, files opened with O_NOFOLLOW.
std::unique_ptr<PackageSource> openDirectorySource(const std::filesystem::path& root);
// A .tar (optionally compressed) or .zip; Error(Usage) when it is neither, Error(Fixity) when
// it starts like one but cannot be read.
std::unique_ptr<PackageSource> openArchiveSource(const std::filesystem::path& file);

}  // namespace surrogate::archive
