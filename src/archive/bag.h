// A BagIt 1.0 bag (RFC 8493) written as a directory, a .tar or a .zip (libarchive).
//
// A bag is a payload (data/...) and tag files describing it:
//
//   bag-info.txt          Payload-Oxum = <bytes>.<files>, Bagging-Date, Bag-Size (of the payload,
//                         decimal units), Bag-Software-Agent, and the user's labels
//                         (Source-Organization, External-Identifier, Contact-Name, ...)
//   bagit.txt             "BagIt-Version: 1.0" / "Tag-File-Character-Encoding: UTF-8"
//   data/...              the payload, byte-identical to its sources
//   manifest-sha256.txt   "<hex>  data/<path>" for every payload file (and -sha512)
//   metadata/...          other tag files (given by the caller, may depend on the digests)
//   tagmanifest-sha256.txt the same for every tag file above (and -sha512)
//
// Every payload file is read once: the same buffer feeds SHA-256, SHA-512 and the output. On a
// machine with two cores or more the two digests run on worker threads beside the write, so
// packing costs about one SHA-512 pass (bench/pack_bench measures it against sha512sum).
// Entries are written in byte order of their paths, with fixed owner (0/0, "root"), fixed
// permissions (0644) and a fixed modification time (SOURCE_DATE_EPOCH when set, else
// 2000-01-01T00:00:00Z), so the same inputs give a byte-identical .tar or .zip. In an archive,
// every entry sits under one top-level folder named after the archive ("pkg.tar" -> "pkg/"), as
// RFC 8493 section 4 asks. The output is written under a temporary name and renamed when
// complete: a partial bag never appears under the final name, and the partial output of a pack
// that was killed is removed by the next pack to the same name (removeStaleParts).
//
//   BagInput in;
//   in.payload = {{"data/original-captures/IMG_1.dng", "/cap/original-captures/IMG_1.dng"}};
//   in.info = {{"Source-Organization", "Museum"}};
//   in.softwareAgent = "Surrogate 0.1.0";
//   in.tagFiles = [](const std::vector<PayloadDigest>& d) { return std::vector<TagFile>{...}; };
//   BagResult r = writeBag(in, "out/capture.zip");
#pragma once

#include <cstdint>
#include <filesystem>
#include <functional>
#include <optional>
#include <string>
#include <utility>
#include <vector>

namespace surrogate::archive {

enum class BagFormat { Directory, Tar, Zip };

// By the output's name: *.tar -> Tar, *.zip -> Zip (any case), anything else a directory.
BagFormat bagFormatFor(const std::filesystem::path& out);
const char* bagFormatName(BagFormat format);  // "directory", "tar", "zip"

struct PayloadSource {
  std::string bagPath;             // "data/..." ('/' separated, UTF-8)
  std::filesystem::path source;    // the file to copy
  std::string expectedSha256;      // optional: must match, else PayloadChanged is thrown
};

struct PayloadDigest {
  std::string bagPath;
  std::uint64_t size = 0;
  std::string sha256, sha512;
};

struct TagFile {
  std::string bagPath;  // e.g. "metadata/mets.xml" (outside data/)
  std::string content;
  // When set, the content is this file's instead, copied in pieces (a METS of 100 000 files is
  // about 450 MB; the packer derives it into a temporary file). It must stay until writeBag
  // returns.
  std::filesystem::path file;
};

struct BagInput {
  std::vector<PayloadSource> payload;
  // bag-info.txt labels after the computed ones, in the given order. Labels Surrogate computes
  // or writes itself (bagInfoLabelProblem) may not be given here.
  std::vector<std::pair<std::string, std::string>> info;
  // The packer's own labels (Surrogate-Package-Identifier, Surrogate-Packaging-Time), written
  // after `info`; only their form is checked.
  std::vector<std::pair<std::string, std::string>> ownInfo;
  // The holder's labels (pack --bag-info: External-Identifier, Contact-Name, ...), written
  // last, in the given order; a label may repeat. Checked as `info` is (bagInfoLabelProblem),
  // and a value may not hold a line break.
  std::vector<std::pair<std::string, std::string>> holderInfo;
  std::string softwareAgent = "Surrogate";
  // Seconds since 1970 for every entry's time and for Bagging-Date. Default: SOURCE_DATE_EPOCH
  // when set, else kDefaultEpoch (see sourceDateEpoch()).
  std::optional<std::int64_t> epoch;
  // Bagging-Date (YYYY-MM-DD). Default: the day of SOURCE_DATE_EPOCH when set, else today (UTC).
  std::string baggingDate;
  // Called once the payload is hashed; returns the other tag files (metadata/...).
  std::function<std::vector<TagFile>(const std::vector<PayloadDigest>&)> tagFiles;
  // Progress: payload bytes done, payload bytes in all.
  std::function<void(std::uint64_t, std::uint64_t)> progress;
  // Whether an existing .tar or .zip of the same name may be replaced (pack --force). Without
  // it the finished package is renamed into place only if the name is still free, so that two
  // packs to one name give one package and one refusal.
  bool replace = false;
};

struct BagResult {
  std::filesystem::path path;
  BagFormat format = BagFormat::Directory;
  std::uint64_t payloadBytes = 0, payloadFiles = 0;
  std::vector<PayloadDigest> payload;  // sorted by bagPath
  std::vector<std::string> tagFiles;   // bag paths of every tag file, sorted
  double seconds = 0;
  // Partial outputs of earlier packs to the same name whose process no longer runs (killed),
  // removed before writing: one sentence each, naming the file and the process.
  std::vector<std::string> removedLeftovers;
};

// 2000-01-01T00:00:00Z: the entries' time when SOURCE_DATE_EPOCH is not set. A fixed instant
// (not "now") keeps repeated packs identical; the real packaging time is in bag-info.txt only
// if the caller puts it there.
inline constexpr std::int64_t kDefaultEpoch = 946684800;
// SOURCE_DATE_EPOCH if set (and a valid number), else kDefaultEpoch.
std::int64_t sourceDateEpoch();
// True when SOURCE_DATE_EPOCH is set to a valid number.
bool sourceDateEpochSet();
// The packaging instant: SOURCE_DATE_EPOCH when set, else now.
std::int64_t packagingEpoch();

// Thrown when a payload file's SHA-256 differs from PayloadSource::expectedSha256 (the file
// changed since it was recorded). Nothing is left under the output name.
class PayloadChanged : public std::runtime_error {
 public:
  PayloadChanged(std::string bagPath, std::string source)
      : std::runtime_error(source + ": changed since it was recorded"),
        bagPath_(std::move(bagPath)), source_(std::move(source)) {}
  const std::string& bagPath() const { return bagPath_; }
  const std::string& source() const { return source_; }

 private:
  std::string bagPath_, source_;
};

// Why `label` cannot be one of the caller's bag-info.txt labels (BagInput::info), or "" when
// it can: Surrogate computes Payload-Oxum, Bagging-Date, Bag-Size and Bag-Software-Agent
// itself and writes Surrogate-Package-Identifier and Surrogate-Packaging-Time (any case), and
// a label has no spaces, colons or control characters (RFC 8493 2.2.2). writeBag refuses such
// a label; the command line checks --meta keys with this same rule, before any work.
std::string bagInfoLabelProblem(const std::string& label);

// Leftovers of writes to `out` that never finished (".NAME.part-PID-N" beside it, from
// AtomicFile) whose process PID no longer runs on this machine: removed, one sentence each
// in the result. A leftover of a process that still runs (another pack writing now) is kept.
// writeBag calls this before writing.
std::vector<std::string> removeStaleParts(const std::filesystem::path& out);

// Checks that `out`'s own name (its last component) can name a package: valid UTF-8 with no
// control character (C0 or C1), no U+FFFE or U+FFFF (an E-ARK SIP's METS names it) and no
// backslash (core/file_names.h, core/text.h needsEscaping: a .tar or .zip holds its bag in a
// folder named after it, whose name verify judges as it judges every path of the package, and
// libarchive cannot record a name that is not UTF-8), and before a .tar or .zip extension a
// folder name other than "." or "..". Throws Error(Input) showing the name escaped, before
// anything is written. checkOutput calls it; the OCFL and E-ARK layouts call it for their folder.
void checkPackageName(const std::filesystem::path& out);

// Checks, before any work, that `out` can be the bag's name: checkPackageName, its folder
// exists, and it is not an existing non-empty folder (directory bags), a folder (archives) or,
// unless `replace` (pack --force), an existing file. Throws Error(Usage), or Error(Input) for
// the name or an existing file.
void checkOutput(const std::filesystem::path& out, bool replace = false);

// Writes the bag. Throws Error(Input) naming an unreadable or changing source file,
// Error(Internal) naming the output when it cannot be written (disk full, no permission),
// Error(Usage) when the output exists as a non-empty directory or an input is malformed.
BagResult writeBag(const BagInput& input, const std::filesystem::path& out);

// RFC 8493 2.1.3 manifest path encoding: '%' -> %25, CR -> %0D, LF -> %0A.
std::string escapeManifestPath(const std::string& path);
// Human-readable size for Bag-Size, e.g. "1.5 GB" (decimal units), "512 bytes".
std::string humanSize(std::uint64_t bytes);
// "YYYY-MM-DD" and "YYYY-MM-DDTHH:MM:SSZ" of seconds since 1970 (UTC).
std::string utcDate(std::int64_t epoch);
std::string utcDateTime(std::int64_t epoch);

}  // namespace surrogate::archive
