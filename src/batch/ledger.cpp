#include "batch/ledger.h"

#include <fcntl.h>
#include <sys/file.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <chrono>
#include <cstdio>
#include <cstring>
#include <ctime>
#include <map>
#include <optional>
#include <type_traits>
#include <variant>
#include <nlohmann/json.hpp>

#include "core/atomic_file.h"
#include "core/error.h"
#include "core/json.h"

namespace surrogate::batch {

namespace {

// A descriptor closed however the function leaves (the flock goes with it).
struct Descriptor {
  int fd = -1;
  ~Descriptor() {
    if (fd >= 0) ::close(fd);
  }
};

int lockWaitingOnSignals(int fd, int operation) {
  int r;
  do r = ::flock(fd, operation);
  while (r != 0 && errno == EINTR);
  return r;
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

std::string ledgerLine(const LedgerEntry& e) {
  JsonWriter j;
  j.beginObject();
  for (const Field& f : kFields) {
    j.key(f.name);
    writeValue(j, e, f.member);
  }
  j.endObject();
  return j.str();
}

bool parseLedgerLine(const std::string& line, LedgerEntry& e) {
  const nlohmann::json j = nlohmann::json::parse(line, nullptr, /*allow_exceptions=*/false);
  if (!j.is_object() || !j.contains("capture") || !j["capture"].is_string() || !j.contains("step") ||
      !j["step"].is_string() || !j.contains("exit") || !j["exit"].is_number_integer())
    return false;
  e = LedgerEntry{};
  for (const Field& f : kFields)
    if (const auto it = j.find(f.name); it != j.end()) readValue(*it, e, f.member);
  return true;
}

void appendToLedger(const std::filesystem::path& ledger, const LedgerEntry& entry) {
  Descriptor d;
  d.fd = ::open(ledger.c_str(), O_RDWR | O_APPEND | O_CREAT | O_CLOEXEC, 0644);
  if (d.fd < 0) throw writeError(ledger, "batch ledger", errno);
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
  Descriptor d;
  d.fd = ::open(ledger.c_str(), O_RDWR | O_APPEND | O_CREAT | O_CLOEXEC, 0644);
  if (d.fd < 0) throw writeError(ledger, "batch ledger", errno);
}

namespace {

// The bytes of the ledger from `offset` to its end, under a shared flock() (no append read
// half-way); nullopt when the file does not exist.
std::optional<std::string> ledgerBytesFrom(const std::filesystem::path& ledger, std::uint64_t offset) {
  Descriptor d;
  d.fd = ::open(ledger.c_str(), O_RDONLY | O_CLOEXEC);
  if (d.fd < 0) {
    if (errno == ENOENT) return std::nullopt;
    throw Error(ErrorKind::Input, ledger.string(), "batch ledger",
                std::string("cannot be read (") + std::strerror(errno) + "); check its permissions");
  }
  lockWaitingOnSignals(d.fd, LOCK_SH);  // no lock on this file system: read without one
  std::string text;
  char buffer[1 << 16];
  for (off_t at = static_cast<off_t>(offset);;) {
    const ssize_t n = ::pread(d.fd, buffer, sizeof buffer, at);
    if (n < 0 && errno == EINTR) continue;
    if (n < 0)
      throw Error(ErrorKind::Input, ledger.string(), "batch ledger",
                  std::string("cannot be read (") + std::strerror(errno) + ")");
    if (n == 0) break;
    text.append(buffer, static_cast<std::size_t>(n));
    at += n;
  }
  return text;
}

// Parses the lines of `text` into `into`; returns the bytes taken: all of them when
// `takePartial` (a last line without its newline is counted damaged), else up to the last
// newline.
std::size_t parseLedgerText(const std::string& text, bool takePartial, Ledger& into) {
  std::size_t begin = 0;
  while (begin < text.size()) {
    std::size_t end = text.find('\n', begin);
    const bool whole = end != std::string::npos;
    if (!whole && !takePartial) break;
    if (!whole) end = text.size();
    const std::string line = text.substr(begin, end - begin);
    begin = std::min(end + 1, text.size());
    if (line.empty()) continue;
    LedgerEntry e;
    if (whole && parseLedgerLine(line, e)) into.entries.push_back(std::move(e));
    else ++into.damagedLines;
  }
  return begin;
}

}  // namespace

Ledger readLedger(const std::filesystem::path& ledger) {
  Ledger out;
  if (const std::optional<std::string> text = ledgerBytesFrom(ledger, 0)) parseLedgerText(*text, true, out);
  return out;
}

std::uint64_t readLedgerSince(const std::filesystem::path& ledger, std::uint64_t offset, Ledger& into) {
  const std::optional<std::string> text = ledgerBytesFrom(ledger, offset);
  return text ? offset + parseLedgerText(*text, false, into) : offset;
}

}  // namespace surrogate::batch

namespace surrogate::batch {

bool ItemStanding::failed() const {
  for (const LedgerEntry* e : lastOfStep)
    if (!e->succeeded()) return true;
  return false;
}

const LedgerEntry* ItemStanding::last(const std::string& step) const {
  for (const LedgerEntry* e : lastOfStep)
    if (e->step == step) return e;
  return nullptr;
}

std::vector<ItemStanding> standings(const Ledger& ledger) {
  std::vector<ItemStanding> out;
  std::map<std::string, std::size_t> index;
  for (const LedgerEntry& e : ledger.entries) {
    auto it = index.find(e.capture);
    if (it == index.end()) {
      it = index.emplace(e.capture, out.size()).first;
      out.push_back(ItemStanding{e.capture, {}, 0, 0});
    }
    ItemStanding& s = out[it->second];
    ++s.attempts;
    if (e.step == "pack" && e.succeeded() && !e.adopted) ++s.packsMade;
    bool replaced = false;
    for (const LedgerEntry*& last : s.lastOfStep)
      if (last->step == e.step) {
        last = &e;
        replaced = true;
      }
    if (!replaced) s.lastOfStep.push_back(&e);
  }
  return out;
}

}  // namespace surrogate::batch
