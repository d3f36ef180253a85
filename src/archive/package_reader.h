// Reading a package (a bag directory, .tar or .zip) without trusting it: the verifier's
// inventory, and the files `surrogate report` shows from a packed bag.
//
// Every entry is checked before anything else happens: its name (safeBagPath: no "..", no
// absolute path, ...), its type (regular files and directories only: no symlink, hard link,
// device, FIFO or socket), duplicates, names that collide after case folding, and limits on
// entry count, sizes and compression ratio (decompression bombs). Archives are streamed through
// libarchive and hashed without being extracted; a bag directory is walked without following
// links and every file is opened with O_NOFOLLOW.
//
//   Inventory inv = readPackage("stela.tar", Limits{});    // hashes and small tag files
//   extractFiles("stela.tar", inv, tempDir, targetOf, Limits{});  // for --reexecute, report
//
// A hostile or malformed package is refused with Error(Usage) naming the entry and the
// problem; a truncated or damaged archive with Error(Fixity).
#pragma once

#include <cstdint>
#include <filesystem>
#include <functional>
#include <map>
#include <optional>
#include <set>
#include <string>
#include <vector>

#include "core/file_names.h"

namespace surrogate::archive {

// Limits on what a package may hold; exceeding one refuses the package.
struct Limits {
  std::uint64_t maxEntries = 1'000'000;        // entries in the package
  std::uint64_t maxTotalBytes = 1ull << 41;    // 2 TiB of content in all
  std::uint64_t maxEntryBytes = 1ull << 39;    // 512 GiB in one file
  double maxRatio = 100;                       // uncompressed / compressed bytes of an archive
  std::uint64_t ratioFloorBytes = 16ull << 20; // the ratio is checked past this many bytes
  std::size_t maxPathLength = kMaxPackagePathBytes;  // bytes in an entry's name (core/file_names.h)
  std::uint64_t maxTagFileBytes = 64ull << 20; // tag files and the carrier are held in memory
};

struct InventoryFile {
  std::uint64_t size = 0;
  std::string sha256, sha512;          // lower-case hex
  // Other digests by BagIt name ("md5", "sha224", ...), only those readPackage is asked for.
  std::map<std::string, std::string> otherDigests;
  // Tag files (outside data/) but the two large derived ones (metadata/mets.xml and crm.rdf,
  // compared by their digests, see readBagFile), and the carrier.
  std::optional<std::string> content;
};

struct Inventory {
  std::string kind;        // "directory", "tar" or "zip" (libarchive's format name otherwise)
  std::string rootPrefix;  // "" or the archive's top folder holding the bag ("stela/")
  std::map<std::string, InventoryFile> files;  // by path relative to the bag root
  std::set<std::string> directories;
  std::uint64_t totalBytes = 0;
  // Files taken out of `files` on purpose (the verifier's unlisted operating-system files):
  // a second read passes over them rather than calling the package changed.
  std::set<std::string> setAside;
};

// Progress: (label, fraction 0..1).
using Progress = std::function<void(const std::string&, double)>;

// Every file's SHA-256 and SHA-512 are computed, and with `otherDigests` (BagIt names, each
// one OpenSSL offers: core/digest.h, namedDigestSize) those too, from the same read, for bags
// made by other tools whose manifests use them (the verifier asks only when such a manifest is
// there).
Inventory readPackage(const std::filesystem::path& package, const Limits& limits,
                      const Progress& progress = {},
                      const std::vector<std::string>& otherDigests = {});

// The content of one file of the bag, read again from the package: the inventory does not hold
// the large tag files (metadata/mets.xml, metadata/crm.rdf), which a check reads only when it
// needs their text. Error(Fixity) if the file is gone or changed since the inventory was made.
std::string readBagFile(const std::filesystem::path& package, const Inventory& inventory,
                        const std::string& path, const Limits& limits);

// Extracts files of the bag into `destination` (which must exist): `targetOf(path)` gives
// the relative destination of a bag path, or an empty path to skip it. Every file is created
// with O_EXCL|O_NOFOLLOW under `destination` only, and its SHA-256 must equal the inventory's
// (the package must not change between the two reads); Error(Fixity) otherwise.
void extractFiles(const std::filesystem::path& package, const Inventory& inventory,
                  const std::filesystem::path& destination,
                  const std::function<std::filesystem::path(const std::string&)>& targetOf,
                  const Limits& limits, const Progress& progress = {});

}  // namespace surrogate::archive
