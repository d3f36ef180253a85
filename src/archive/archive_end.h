// Private to src/archive: whether a .tar or .zip read through libarchive ends where it should,
// neither cut short nor followed by other data (archive_end.cpp).
#pragma once

#include <cstddef>
#include <cstdint>
#include <optional>
#include <string>

namespace surrogate::archive {

// The block structure of an uncompressed tar, followed byte by byte as the archive is read
// (libarchive takes an archive cut at an entry boundary, or followed by a second archive, for a
// whole one): 512-byte headers, each followed by its data padded to 512 bytes, then the
// end-of-archive marker (two zero blocks), then only whole 512-byte blocks of zeros (the padding
// of the last record).
class TarLayout {
 public:
  // The next `n` bytes of the file.
  void feed(const char* data, std::size_t n);

  // Why the archive that ended after everything fed is not whole, or "" when it is.
  // `truncation` says which kind: true for a cut, false for data after the end.
  std::string problem(bool& truncation) const;

 private:
  enum class State { Header, SecondZero, Padding };

  static bool zero(const std::string& block);
  // A numeric header field: octal digits (leading spaces or NULs), or base-256 (GNU, high bit).
  static std::optional<std::uint64_t> number(const char* field, std::size_t size);
  // "size=" of a pax extended header ("<length> <key>=<value>\n" records), if it has one.
  static std::optional<std::uint64_t> paxSize(const std::string& text);
  void header(std::uint64_t at);

  State state_ = State::Header;
  std::string block_;
  std::uint64_t offset_ = 0, skip_ = 0, collect_ = 0, endAt_ = 0;
  bool collecting_ = false;
  std::string pax_;
  std::optional<std::uint64_t> paxSize_, trailingAt_;
  std::optional<std::string> broken_;
};

// The end of a zip (open as `fd`, `fileSize` bytes, of which `entriesRead` entries were read):
// the end-of-central-directory record (and, for zip64, its locator and record) must end exactly
// at the end of the file, and the central directory must end where they begin. Returns why
// not, or "" when it is whole; `truncation` says which kind.
std::string zipEndProblem(int fd, std::uint64_t fileSize, std::uint64_t entriesRead, bool& truncation);

}  // namespace surrogate::archive
