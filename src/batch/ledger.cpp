#include "batch/ledger.h"

#include <fcntl.h>
#include <sys/file.h>
#include <sys/stat.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <chrono>
#include <cstdio>
#include <cstring>
#include <ctime>
#include <optional>
#include <type_traits>
#include <variant>
#include <nlohmann/json.hpp>

#include "batch/descriptor.h"
#include "capture/output_rule.h"
#include "core/atomic_file.h"
#include "core/error.h"
#include "core/json.h"
#include "core/text.h"

namespace surrogate::batch {

namespace {

int lockWaitingOnSignals(int fd, int operation) {
  int r;
  do r = ::flock(fd, operation);
  while (r != 0 && errno == EINTR);
  return r;
}

[[noreturn]] void refuseLedger(const std::filesystem::path& ledger, const std::string& why) {
  throw Error(ErrorKind::Input, escapedText(ledger.string()), "batch ledger", why);
}

[[noreturn]] void refuseTooLarge(const std::filesystem::path& ledger) {
  refuseLedger(ledger, "is larger than " + std::to_string(kMaxLedgerBytes >> 20) +
                           " MiB, more than any batch writes (about 700 bytes a step): it is not a ledger, or "
                           "one to close: start a new ledger for the rest of the work");
}

// A ledger path naming a file of type `mode` that is not a regular one.
[[noreturn]] void refuseNotRegular(const std::filesystem::path& ledger, mode_t mode) {
  refuseLedger(ledger, "is " + capture::fileTypeName(mode) + ", not a regular file: a ledger is a file that "
                       "surrogate batch -o writes; give a file name");
}

// A path that names something other than a regular file is refused before it is opened (a
// device can act on being opened, a tape rewinding); `follow`: as the path's last link leads.
void requireRegularBeforeOpening(const std::filesystem::path& ledger, bool follow) {
  struct stat st {};
  if ((follow ? ::stat(ledger.c_str(), &st) : ::lstat(ledger.c_str(), &st)) != 0) return;  // open() says why
  if (S_ISLNK(st.st_mode))
    refuseLedger(ledger, "is a symbolic link: Surrogate never writes through one; give the ledger's own name");
  if (!S_ISREG(st.st_mode)) refuseNotRegular(ledger, st.st_mode);
}

// The checks on the descriptor itself: what the path names may have changed since the command
// line was checked, and appending writes through every name of a file.
void requireLedgerFile(const std::filesystem::path& ledger, int fd, bool writing) {
  struct stat st {};
  if (::fstat(fd, &st) != 0) throw writeError(ledger, "batch ledger", errno);
  if (!S_ISREG(st.st_mode)) refuseNotRegular(ledger, st.st_mode);
  if (writing && st.st_nlink > 1)
    refuseLedger(ledger, "has " + std::to_string(st.st_nlink) + " names (hard links), and appending would "
                         "change the file under each of them; give a ledger of its own");
}

// Opens the ledger to append, making it when absent: never through a symbolic link, never
// waiting on a FIFO.
int openToAppend(const std::filesystem::path& ledger) {
  requireRegularBeforeOpening(ledger, false);
  const int fd = ::open(ledger.c_str(), O_RDWR | O_APPEND | O_CREAT | O_CLOEXEC | O_NOFOLLOW | O_NONBLOCK, 0644);
  if (fd < 0 && errno == ELOOP)
    refuseLedger(ledger, "is a symbolic link: Surrogate never writes through one; give the ledger's own name");
  if (fd < 0 && (errno == EISDIR || errno == ENXIO || errno == ENODEV))
    refuseLedger(ledger, "is not a regular file: a ledger is a file that surrogate batch -o writes; give a file name");
  if (fd < 0) throw writeError(ledger, "batch ledger", errno);
  Descriptor d{fd};
  requireLedgerFile(ledger, fd, true);
  d.fd = -1;
  return fd;
}

// Opens the ledger to read, following links; -1 when it does not exist. A FIFO opened without
// blocking is refused by its type before anything is read.
int openToRead(const std::filesystem::path& ledger) {
  requireRegularBeforeOpening(ledger, true);
  const int fd = ::open(ledger.c_str(), O_RDONLY | O_CLOEXEC | O_NONBLOCK);
  if (fd < 0) {
    if (errno == ENOENT) return -1;
    refuseLedger(ledger, std::string("cannot be read (") + std::strerror(errno) + "); check its permissions");
  }
  Descriptor d{fd};
  requireLedgerFile(ledger, fd, false);
  struct stat st {};
  if (::fstat(fd, &st) == 0 && static_cast<std::uint64_t>(st.st_size) > kMaxLedgerBytes) refuseTooLarge(ledger);
  d.fd = -1;
  return fd;
}

}  // namespace

std::string ledgerTime() {
  const auto now = std::chrono::system_clock::now();
  const auto ms = std::chrono::duration_cast<std::chrono::milliseconds>(now.time_since_epoch()).count();
  const std::time_t seconds = static_cast<std::time_t>(ms / 1000);
  std::tm utc{};
  gmtime_r(&seconds, &utc);
  char text[64];
  std::snprintf(text, sizeof text, "%04d-%02d-%02dT%02d:%02d:%02d.%03dZ", utc.tm_year + 1900, utc.tm_mon + 1,
                utc.tm_mday, utc.tm_hour, utc.tm_min, utc.tm_sec, static_cast<int>(ms % 1000));
  return text;
}

namespace {

// Every member of a ledger line, in the order a line lists them: the one list the writer and
// the reader follow.
using Member = std::variant<std::string LedgerEntry::*, int LedgerEntry::*, double LedgerEntry::*,
                            std::uint64_t LedgerEntry::*, std::int64_t LedgerEntry::*, bool LedgerEntry::*>;
struct Field {
  const char* name;
  Member member;
};
const Field kFields[] = {
    {"capture", &LedgerEntry::capture},
    {"step", &LedgerEntry::step},
    {"attempt", &LedgerEntry::attempt},
    {"start", &LedgerEntry::start},
    {"end", &LedgerEntry::end},
    {"seconds", &LedgerEntry::seconds},
    {"exit", &LedgerEntry::exit},
    {"message", &LedgerEntry::message},
    {"package", &LedgerEntry::package},
    {"packageId", &LedgerEntry::packageId},
    {"carrierSha256", &LedgerEntry::carrierSha256},
    {"packageSha256", &LedgerEntry::packageSha256},
    {"packageSize", &LedgerEntry::packageSize},
    {"packageMtimeNs", &LedgerEntry::packageMtimeNs},
    {"peakMemory", &LedgerEntry::peakMemory},
    {"memoryBudget", &LedgerEntry::memoryBudget},
    {"reexecuted", &LedgerEntry::reexecuted},
    {"adopted", &LedgerEntry::adopted},
    {"host", &LedgerEntry::host},
    {"version", &LedgerEntry::version},
};

// How every line the writer makes begins (kFields' first member, JsonWriter's compact form; a
// package item's line names it first as "package"): what a torn first line still shows of a ledger.
constexpr const char* kLedgerLineStart = "{\"capture\":";
constexpr const char* kPackageLineStart = "{\"package\":";

template <class>
inline constexpr bool kAlwaysFalse = false;

void writeValue(JsonWriter& j, const LedgerEntry& e, const Member& member) {
  std::visit(
      [&](auto pointer) {
        const auto& value = e.*pointer;
        using T = std::decay_t<decltype(value)>;
        if constexpr (std::is_same_v<T, std::uint64_t>) j.value(static_cast<unsigned long long>(value));
        else if constexpr (std::is_same_v<T, std::int64_t>) j.value(static_cast<long long>(value));
        else j.value(value);
      },
      member);
}

// The member's value from `v` when it has the member's type; else the member keeps its default.
void readValue(const nlohmann::json& v, LedgerEntry& e, const Member& member) {
  std::visit(
      [&](auto pointer) {
        auto& value = e.*pointer;
        using T = std::decay_t<decltype(value)>;
        if constexpr (std::is_same_v<T, std::string>) {
          if (v.is_string()) value = v.get<std::string>();
        } else if constexpr (std::is_same_v<T, bool>) {
          if (v.is_boolean()) value = v.get<bool>();
        } else if constexpr (std::is_same_v<T, double>) {
          if (v.is_number()) value = v.get<double>();
        } else if constexpr (std::is_integral_v<T>) {
          if (v.is_number_integer()) value = v.get<T>();
        } else {
          static_assert(kAlwaysFalse<T>, "a ledger member of a type the reader does not know");
        }
      },
      member);
}

}  // namespace

namespace {

// The message within kMaxLedgerMessageBytes, cut at a character's start and saying so: every
// other member is bounded by what it is (a path, a digest, a time), so the line stays well
// within kMaxLedgerLineBytes, which the reader holds to.
std::string boundedMessage(const std::string& message) {
  if (message.size() <= kMaxLedgerMessageBytes) return message;
  std::size_t cut = kMaxLedgerMessageBytes;
  while (cut > 0 && (static_cast<unsigned char>(message[cut]) & 0xC0) == 0x80) --cut;
  return message.substr(0, cut) + " ... (" + std::to_string(message.size() - cut) + " more bytes left out)";
}

}  // namespace

std::string ledgerLine(const LedgerEntry& entry) {
  LedgerEntry e = entry;
  e.message = boundedMessage(entry.message);
  JsonWriter j;
  j.beginObject();
  if (e.packageItem) j.key("package").value(e.capture);
  for (const Field& f : kFields) {
    if (e.packageItem && (std::strcmp(f.name, "capture") == 0 || std::strcmp(f.name, "package") == 0)) continue;
    j.key(f.name);
    writeValue(j, e, f.member);
  }
  j.endObject();
  return j.str();
}

bool parseLedgerLine(const std::string& line, LedgerEntry& e) {
  const nlohmann::json j = nlohmann::json::parse(line, nullptr, /*allow_exceptions=*/false);
  if (!j.is_object() || !j.contains("step") || !j["step"].is_string() || !j.contains("exit") ||
      !j["exit"].is_number_integer())
    return false;
  const bool hasCapture = j.contains("capture") && j["capture"].is_string();
  if (!hasCapture && !(j.contains("package") && j["package"].is_string())) return false;
  e = LedgerEntry{};
  for (const Field& f : kFields)
    if (const auto it = j.find(f.name); it != j.end()) readValue(*it, e, f.member);
  // A package item: named "package" alone; or, in a ledger written before it was, a
  // verification whose "capture" is its package.
  if (!hasCapture) e.capture = e.package;
  e.packageItem = !hasCapture || (e.step == "verify" && !e.package.empty() && e.capture == e.package);
  return true;
}

void appendToLedger(const std::filesystem::path& ledger, const LedgerEntry& entry) {
  Descriptor d{openToAppend(ledger)};
  if (lockWaitingOnSignals(d.fd, LOCK_EX) != 0) throw writeError(ledger, "batch ledger", errno);
  std::string line = ledgerLine(entry) + "\n";
  // A process killed in the middle of its append left a line without its newline: this one
  // starts on a line of its own, so that only the torn line is lost.
  const off_t size = ::lseek(d.fd, 0, SEEK_END);
  if (size > 0) {
    char last = '\n';
    if (::pread(d.fd, &last, 1, size - 1) == 1 && last != '\n') line.insert(line.begin(), '\n');
  }
  // One write() of the whole line: a regular file takes it whole or reports why not.
  std::size_t done = 0;
  while (done < line.size()) {
    const ssize_t n = ::write(d.fd, line.data() + done, line.size() - done);
    if (n < 0 && errno == EINTR) continue;
    if (n <= 0) throw writeError(ledger, "batch ledger", n < 0 ? errno : ENOSPC);
    done += static_cast<std::size_t>(n);
  }
  // The line is on disk before the next step trusts it (a crash of the machine must not lose
  // the record of a finished pack and make the next batch pack again).
  if (::fdatasync(d.fd) != 0 && errno != EINVAL) throw writeError(ledger, "batch ledger", errno);
}

void requireWritableLedger(const std::filesystem::path& ledger) {
  Descriptor d{openToAppend(ledger)};
}

namespace {

// Reads the lines of the open ledger from byte `offset` into `into`, one at a time, none held
// past kMaxLedgerLineBytes (a longer one is counted damaged); returns the bytes taken: to the
// end when `takePartial` (a last line without its newline is counted damaged), else up to the
// last newline.
std::uint64_t readLines(const std::filesystem::path& ledger, int fd, std::uint64_t offset, bool takePartial,
                        Ledger& into) {
  std::string line;
  bool overlong = false;
  std::uint64_t at = offset, lineStart = offset;
  const auto endLine = [&] {
    LedgerEntry e;
    if (overlong) ++into.damagedLines;
    else if (line.empty()) return;
    else if (parseLedgerLine(line, e)) into.entries.push_back(std::move(e));
    else ++into.damagedLines;
  };
  static thread_local char buffer[1 << 16];
  for (;;) {
    const ssize_t n = ::pread(fd, buffer, sizeof buffer, static_cast<off_t>(at));
    if (n < 0 && errno == EINTR) continue;
    if (n < 0) refuseLedger(ledger, std::string("cannot be read (") + std::strerror(errno) + ")");
    if (n == 0) break;
    if (at + static_cast<std::uint64_t>(n) > kMaxLedgerBytes) refuseTooLarge(ledger);  // grew, or a size of 0 lied
    for (const char *p = buffer, *end = buffer + n; p < end;) {
      const char* newline = static_cast<const char*>(std::memchr(p, '\n', static_cast<std::size_t>(end - p)));
      const char* stop = newline ? newline : end;
      if (!overlong && line.size() + static_cast<std::size_t>(stop - p) > kMaxLedgerLineBytes) {
        overlong = true;
        std::string().swap(line);
      }
      if (!overlong) line.append(p, stop);
      if (!newline) break;
      endLine();
      line.clear();
      overlong = false;
      lineStart = at + static_cast<std::uint64_t>(newline + 1 - buffer);
      p = newline + 1;
    }
    at += static_cast<std::uint64_t>(n);
  }
  if (line.empty() && !overlong) return at;
  if (!takePartial) return lineStart;
  ++into.damagedLines;
  return at;
}

// Reads from `offset` under a shared flock() (no append read half-way); `offset` back when the
// ledger does not exist.
std::uint64_t readLedgerFrom(const std::filesystem::path& ledger, std::uint64_t offset, bool takePartial,
                             Ledger& into) {
  Descriptor d{openToRead(ledger)};
  if (d.fd < 0) return offset;
  lockWaitingOnSignals(d.fd, LOCK_SH);  // no lock on this file system: read without one
  return readLines(ledger, d.fd, offset, takePartial, into);
}

}  // namespace

Ledger readLedger(const std::filesystem::path& ledger) {
  Ledger out;
  readLedgerFrom(ledger, 0, true, out);
  return out;
}

std::uint64_t readLedgerSince(const std::filesystem::path& ledger, std::uint64_t offset, Ledger& into) {
  return readLedgerFrom(ledger, offset, false, into);
}

void checkLedgerTarget(const std::filesystem::path& ledger, const std::filesystem::path& list) {
  namespace fs = std::filesystem;
  std::error_code ec;
  if (ledger.empty()) refuseLedger(ledger, "is no name: give the ledger's file name, e.g. -o ledger.jsonl");
  if (list != "-" && fs::exists(ledger, ec) && fs::equivalent(ledger, list, ec))
    refuseLedger(ledger, "is the list of the batch itself, which the ledger's lines would damage; give the "
                         "ledger a name of its own, e.g. -o ledger.jsonl");
  if (fs::is_directory(fs::symlink_status(ledger, ec)))
    refuseLedger(ledger, "is a folder; give the ledger's file name, e.g. -o " + (ledger / "ledger.jsonl").string());
  capture::checkOutputTarget(ledger, "-o", capture::ExistingOutput::ReplaceOutput,
                             capture::OutputPlace::OutsideCaptures);
  // The ledger's first line, read as the reader reads (regular, bounded).
  Descriptor d{openToRead(ledger)};
  if (d.fd < 0) return;
  lockWaitingOnSignals(d.fd, LOCK_SH);
  std::string head(kMaxLedgerLineBytes + 1, '\0');
  ssize_t n;
  do n = ::pread(d.fd, head.data(), head.size(), 0);
  while (n < 0 && errno == EINTR);
  if (n <= 0) return;  // empty: a ledger made by requireWritableLedger, or one to start
  head.resize(static_cast<std::size_t>(n));
  const std::size_t newline = head.find('\n');
  LedgerEntry e;
  const bool isLedger = newline != std::string::npos
                            ? parseLedgerLine(head.substr(0, newline), e)
                            : head.size() <= kMaxLedgerLineBytes && (head.rfind(kLedgerLineStart, 0) == 0 ||
                                                                     head.rfind(kPackageLineStart, 0) == 0);
  if (!isLedger)
    refuseLedger(ledger, "is not a ledger: its first line is not a line surrogate batch writes, so it is some "
                         "other file, which appending would damage; give a new file name for the ledger");
}

}  // namespace surrogate::batch
