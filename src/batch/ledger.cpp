#include "batch/ledger.h"

#include <fcntl.h>
#include <sys/file.h>
#include <unistd.h>

#include <cerrno>
#include <chrono>
#include <cstdio>
#include <cstring>
#include <ctime>
#include <map>
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

std::string ledgerLine(const LedgerEntry& e) {
  JsonWriter j;
  j.beginObject()
      .key("capture").value(e.capture)
      .key("step").value(e.step)
      .key("attempt").value(e.attempt)
      .key("start").value(e.start)
      .key("end").value(e.end)
      .key("seconds").value(e.seconds)
      .key("exit").value(e.exit)
      .key("message").value(e.message)
      .key("package").value(e.package)
      .key("packageId").value(e.packageId)
      .key("carrierSha256").value(e.carrierSha256)
      .key("packageSha256").value(e.packageSha256)
      .key("packageSize").value(static_cast<unsigned long long>(e.packageSize))
      .key("packageMtimeNs").value(static_cast<long long>(e.packageMtimeNs))
      .key("peakMemory").value(static_cast<unsigned long long>(e.peakMemory))
      .key("memoryBudget").value(static_cast<unsigned long long>(e.memoryBudget))
      .key("reexecuted").value(e.reexecuted)
      .key("adopted").value(e.adopted)
      .key("host").value(e.host)
      .key("version").value(e.version)
      .endObject();
  return j.str();
}

bool parseLedgerLine(const std::string& line, LedgerEntry& e) {
  const nlohmann::json j = nlohmann::json::parse(line, nullptr, /*allow_exceptions=*/false);
  if (!j.is_object() || !j.contains("capture") || !j["capture"].is_string() || !j.contains("step") ||
      !j["step"].is_string() || !j.contains("exit") || !j["exit"].is_number_integer())
    return false;
  const auto text = [&](const char* key) {
    return j.contains(key) && j[key].is_string() ? j[key].get<std::string>() : std::string();
  };
  const auto number = [&](const char* key, auto fallback) {
    using T = decltype(fallback);
    return j.contains(key) && j[key].is_number() ? j[key].get<T>() : fallback;
  };
  e = LedgerEntry{};
  e.capture = text("capture");
  e.step = text("step");
  e.attempt = number("attempt", 1);
  e.start = text("start");
  e.end = text("end");
  e.seconds = number("seconds", 0.0);
  e.exit = j["exit"].get<int>();
  e.message = text("message");
  e.package = text("package");
  e.packageId = text("packageId");
  e.carrierSha256 = text("carrierSha256");
  e.packageSha256 = text("packageSha256");
  e.packageSize = number("packageSize", std::uint64_t{0});
  e.packageMtimeNs = number("packageMtimeNs", std::int64_t{0});
  e.peakMemory = number("peakMemory", std::uint64_t{0});
  e.memoryBudget = number("memoryBudget", std::uint64_t{0});
  const auto flag = [&](const char* key) { return j.contains(key) && j[key].is_boolean() && j[key].get<bool>(); };
  e.reexecuted = flag("reexecuted");
  e.adopted = flag("adopted");
  e.host = text("host");
  e.version = text("version");
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

Ledger readLedger(const std::filesystem::path& ledger) {
  Ledger out;
  Descriptor d;
  d.fd = ::open(ledger.c_str(), O_RDONLY | O_CLOEXEC);
  if (d.fd < 0) {
    if (errno == ENOENT) return out;
    throw Error(ErrorKind::Input, ledger.string(), "batch ledger",
                std::string("cannot be read (") + std::strerror(errno) + "); check its permissions");
  }
  lockWaitingOnSignals(d.fd, LOCK_SH);  // no lock on this file system: read without one
  std::string text;
  char buffer[1 << 16];
  for (;;) {
    const ssize_t n = ::read(d.fd, buffer, sizeof buffer);
    if (n < 0 && errno == EINTR) continue;
    if (n < 0)
      throw Error(ErrorKind::Input, ledger.string(), "batch ledger",
                  std::string("cannot be read (") + std::strerror(errno) + ")");
    if (n == 0) break;
    text.append(buffer, static_cast<std::size_t>(n));
  }
  std::size_t begin = 0;
  while (begin < text.size()) {
    std::size_t end = text.find('\n', begin);
    const bool whole = end != std::string::npos;
    if (!whole) end = text.size();
    const std::string line = text.substr(begin, end - begin);
    begin = end + 1;
    if (line.empty()) continue;
    LedgerEntry e;
    if (whole && parseLedgerLine(line, e)) out.entries.push_back(std::move(e));
    else ++out.damagedLines;
  }
  return out;
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
