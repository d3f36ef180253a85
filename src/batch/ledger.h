// The ledger of a batch: one JSON line per job, step and attempt, appended to a file that
// several batches (GNU parallel's jobs, a Slurm array's tasks) share.
//
// An append is one write() of one whole line to a file opened with O_APPEND, under an
// exclusive flock() of that file: lines from several processes never interleave, whatever
// their length (a line is longer than PIPE_BUF when a message lists many files). A process
// killed meanwhile leaves at most a last line without its newline, which readLedger skips
// (and counts) and the next append starts on a line of its own.
//
//   appendToLedger("ledger.jsonl", entry);
//   const Ledger ledger = readLedger("ledger.jsonl");
#pragma once

#include <cstdint>
#include <filesystem>
#include <string>
#include <vector>

namespace surrogate::batch {

// One attempt of one step on one item of the list. The member names are the ledger's keys, but
// for a package item (verify --batch, a package in a batch's list): its line names the item
// "package" and has no "capture", a package being no capture.
struct LedgerEntry {
  std::string capture;          // the item as the list gives it: a capture folder or a package
  bool packageItem = false;     // the item is a package (its line: "package", no "capture")
  std::string step;             // "run", "pack" or "verify"
  int attempt = 1;              // 1, 2, ... for this item and step, across batches
  std::string start, end;       // UTC, ISO 8601 with milliseconds
  double seconds = 0;           // end - start
  int exit = 0;                 // the command's exit code; 128 + N when signal N ended it
  std::string message;          // what went wrong in the command's own words, or what was done
  std::string package;          // the package written or checked, "" for run
  std::string packageId;        // its identifier (urn:surrogate:package:...), "" when unknown
  std::string carrierSha256;    // the capture's carrier after the step ("" for a package item)
  std::string packageSha256;    // the package after the step (see resume.h, packageState)
  std::uint64_t packageSize = 0;
  std::int64_t packageMtimeNs = 0;  // modification time, nanoseconds since 1970
  std::uint64_t peakMemory = 0;     // bytes: the job's peak resident memory (wait4's ru_maxrss)
  std::uint64_t memoryBudget = 0;   // bytes: --memory, 0 when none was given
  bool reexecuted = false;      // verify: with --reexecute
  bool adopted = false;         // pack: a package found made, recorded without packing again
  std::string host;             // where it ran
  std::string version;          // Surrogate's version

  bool succeeded() const { return exit == 0; }
};

struct Ledger {
  std::vector<LedgerEntry> entries;  // in file order
  std::size_t damagedLines = 0;      // lines that are not a ledger entry (a torn last line)
};

// The entry as one line of JSON, without the newline.
std::string ledgerLine(const LedgerEntry& entry);
// Parses one line; false when it is not a ledger entry.
bool parseLedgerLine(const std::string& line, LedgerEntry& entry);

// What a ledger may be. No line the writer makes is longer than kMaxLedgerLineBytes (it cuts a
// message past kMaxLedgerMessageBytes); a longer line is read as damaged, without being held.
// A ledger past kMaxLedgerBytes is refused: a step's line is about 700 bytes, so 100 000
// captures of three steps are some 210 MB, and the reader holds every entry in memory.
inline constexpr std::size_t kMaxLedgerMessageBytes = 64 << 10;
inline constexpr std::size_t kMaxLedgerLineBytes = 1 << 20;
inline constexpr std::uint64_t kMaxLedgerBytes = 512ull << 20;

// The ledger a batch is told to write (`-o LEDGER` of `batch` and `verify --batch`), checked
// before any job: the output rule of capture/output_rule.h, outside every capture (a pack would
// bag it while it grows), not a folder, not the batch's `list` ("-" for standard input: none),
// and, when it exists and is not empty, a ledger: its first line a ledger entry (or the start
// of one, a writer's torn first line). Anything else is some other file, which appending would
// damage. Throws Error(Input) (exit 1) naming the ledger and why.
void checkLedgerTarget(const std::filesystem::path& ledger, const std::filesystem::path& list);

// Appends the entry as one line: see the header comment. Throws Error(Input) when the ledger is
// not a regular file of one name (a symbolic link, a FIFO, a device, a hard link: the checks of
// checkLedgerTarget that need no reading, made again on the descriptor written), Error(Internal)
// naming the ledger when it cannot be written (a full disk, no permission).
void appendToLedger(const std::filesystem::path& ledger, const LedgerEntry& entry);

// Opens the ledger for appending (making it when absent) and closes it: a ledger that cannot be
// written is reported before any job runs. Throws as appendToLedger.
void requireWritableLedger(const std::filesystem::path& ledger);

// Reads the whole ledger (an absent file: an empty ledger), under a shared flock() so that no
// append is read half-way, one bounded line at a time. Throws Error(Input) when the file cannot
// be read, is not a regular file (a FIFO is refused without waiting for a writer, a device such
// as /dev/zero without reading it) or is larger than kMaxLedgerBytes.
Ledger readLedger(const std::filesystem::path& ledger);

// The lines appended since byte `offset` (where an earlier read ended), added to `into`, read
// as readLedger reads; returns where this read ended: after the last whole line. A last line
// without its newline (a killed writer's) is left for a later read, which counts it damaged
// once the next append has ended it. A batch running beside others (GNU parallel's jobs, a
// Slurm array's tasks, a second batch on the same list) sees their progress this way.
std::uint64_t readLedgerSince(const std::filesystem::path& ledger, std::uint64_t offset, Ledger& into);

// Now, as the ledger writes times: "2026-12-05T05:01:02.345Z".
std::string ledgerTime();

}  // namespace surrogate::batch
