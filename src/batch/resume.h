// What a batch finds done and still valid, from its ledger and the files as they are now, so
// that running the same batch again does only what is left.
//
// A step is done when its last attempt in the ledger succeeded (the latest attempt decides, as
// in --summary) and a success of it has digests that still describe the files:
//   run     the carrier's SHA-256 recorded after the run is the carrier's now;
//   pack    the same, and the package's SHA-256 recorded after the pack is the package's now;
//   verify  the package's SHA-256 recorded when it was verified is the package's now (and it
//           was re-executed, when --reexecute is asked for).
// A package is read again only when its size or modification time differ from the ledger's
// record (packageState): a pack or verify done is not undone by reading every package again.
#pragma once

#include <cstdint>
#include <filesystem>
#include <string>
#include <vector>

#include "batch/ledger.h"

namespace surrogate::batch {

// A file (or a folder package) as it is now.
struct FileState {
  bool exists = false;
  std::string sha256;  // "" when it does not exist
  std::uint64_t size = 0;
  std::int64_t mtimeNs = 0;
};

// The capture's carrier (CAPTURE/assembly-files/carrier.xml).
FileState carrierState(const std::filesystem::path& capture);
// A package: a .zip or .tar file's SHA-256; for a folder package, that of its
// tagmanifest-sha256.txt (which covers the manifests, which cover every file), with that
// file's size and time. When `known` records the same size and modification time, its SHA-256
// is taken without reading the package.
FileState packageState(const std::filesystem::path& package, const LedgerEntry* known = nullptr);

// The ledger's entries for one item and step, in file order.
struct StepHistory {
  std::vector<const LedgerEntry*> attempts;
  const LedgerEntry* lastSuccess() const;
  int nextAttempt() const { return static_cast<int>(attempts.size()) + 1; }
};
StepHistory historyOf(const Ledger& ledger, const std::string& item, const std::string& step);

// Whether the step is done and still valid (see the header comment); `why` says why not, in
// words for --dry-run ("no run recorded", "the carrier changed since the run", ...).
bool runStillValid(const StepHistory& run, const FileState& carrier, std::string& why);
bool packStillValid(const StepHistory& pack, const FileState& carrier, const FileState& package,
                    std::string& why);
bool verifyStillValid(const StepHistory& verify, const FileState& package, bool reexecute, std::string& why);

// `count` items of `total` (their indices, ascending), drawn with a seed: the same seed and
// lists give the same draw on every machine (a Mersenne twister, specified by C++, and
// Fisher-Yates on it). All of them when count >= total.
std::vector<std::size_t> drawSample(std::size_t total, std::size_t count, std::uint64_t seed);

}  // namespace surrogate::batch

namespace surrogate::batch {

// The positions of the items the ledger records no successful verification of (re-executed,
// when `reexecute`), from the ledger alone: what a sampled audit draws from, so that runs with
// the same ledger go through the whole list before repeating a package.
std::vector<std::size_t> notYetVerified(const std::vector<std::string>& items, const Ledger& ledger, bool reexecute);

}  // namespace surrogate::batch
