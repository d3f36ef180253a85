// The list a batch works through: capture folders or packages, one a line, and where each
// capture's package goes.
#pragma once

#include <filesystem>
#include <istream>
#include <string>
#include <vector>

namespace surrogate::batch {

// One line of the list. A relative path is read from the list file's folder (from the
// current folder for standard input), so that a list means the same from any working folder;
// the ledger names the item by its line, as written, which stays the same too.
struct WorkItem {
  std::size_t number = 0;  // 1-based among the items (what --one N and a Slurm task count)
  std::string path;        // as the line gives it: the item's name in the ledger and on screen
  std::string location;    // where it is: `path` read from the list's folder ("" : `path`)
  bool isPackage = false;  // a .zip or .tar file, or a folder holding bagit.txt
  const std::string& where() const { return location.empty() ? path : location; }
};

// A list's bounds: a backlog of 100 000 captures with paths of 200 bytes is 20 MB; a line is a
// path, at most PATH_MAX. What passes them is no list (/dev/zero on standard input, a binary
// file given by mistake), refused before it fills the memory.
inline constexpr std::size_t kMaxListBytes = 64u << 20;
inline constexpr std::size_t kMaxListLineBytes = 4096;

// The items of a list: one path a line, a relative one read from `base` ("" : the current
// folder); blank lines and lines starting with # are not items,
// a line's trailing spaces and carriage return (a list written on Windows) are dropped.
// Throws Error(Usage) naming both lines for a line that names an earlier item again, compared
// by real path (a symbolic link to it, its absolute path: the same capture twice would be two
// jobs on one capture); Error(Input) for text that is no list: a NUL byte, more than
// kMaxListBytes, a line longer than kMaxListLineBytes.
std::vector<WorkItem> readWorkList(std::istream& in, const std::string& listName,
                                   const std::filesystem::path& base = {});
// The same from a file, its relative paths read from its folder, or standard input when `list`
// is "-". Error(Input) when it cannot be
// read or is not a regular file (a FIFO, a device: refused without reading), Error(Usage) when
// it holds no item.
std::vector<WorkItem> readWorkList(const std::string& list);

// The sentence a batch prints once before its jobs when some item of `list` is a relative path:
// the folder they are read from, in full ("" when every item is absolute).
std::string listFolderNote(const std::string& list, const std::vector<WorkItem>& items);

// A path as one argument of a command: "./" before a relative path starting with '-', which
// the command would take as an option (an item "--help", a capture folder "-h").
std::string pathArgument(const std::string& path);

// Whether a path names a package rather than a capture: a .zip or .tar file, or a folder
// holding bagit.txt.
bool looksLikePackage(const std::filesystem::path& path);

// The package a capture is packed into: DIR/NAME.zip with --packages DIR, else NAME.zip beside
// the capture (NAME: the capture folder's name); `format` "tar" makes it NAME.tar (--package-
// format), which pack writes as a tar.
std::filesystem::path packagePathFor(const std::filesystem::path& capture, const std::filesystem::path& packagesDir,
                                     const std::string& format = "zip");

// Refuses, with Error(Usage) naming both lines, two captures of the list whose packages would
// be the same file (two folders of one name packed into one --packages folder).
void requireDistinctPackages(const std::vector<WorkItem>& items, const std::filesystem::path& packagesDir,
                             const std::string& format = "zip");

}  // namespace surrogate::batch
