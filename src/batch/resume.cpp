#include "batch/resume.h"

#include <sys/stat.h>

#include <algorithm>
#include <numeric>
#include <limits>
#include <random>
#include <set>

#include "capture/capture.h"
#include "core/digest.h"

namespace surrogate::batch {

namespace fs = std::filesystem;

namespace {

bool statOf(const fs::path& path, FileState& s) {
  struct stat st {};
  if (::stat(path.c_str(), &st) != 0 || !S_ISREG(st.st_mode)) return false;
  s.exists = true;
  s.size = static_cast<std::uint64_t>(st.st_size);
  s.mtimeNs = static_cast<std::int64_t>(st.st_mtim.tv_sec) * 1'000'000'000 + st.st_mtim.tv_nsec;
  return true;
}

}  // namespace

FileState carrierState(const fs::path& capture) {
  FileState s;
  const fs::path file = capture / capture::kCarrierPath;
  if (!statOf(file, s)) return s;
  s.sha256 = digestFile(file).sha256;
  return s;
}

FileState packageState(const fs::path& package, const LedgerEntry* known) {
  FileState s;
  std::error_code ec;
  const fs::path file = fs::is_directory(package, ec) ? package / "tagmanifest-sha256.txt" : package;
  if (!statOf(file, s)) return FileState{};
  if (known && !known->packageSha256.empty() && known->packageSize == s.size && known->packageMtimeNs == s.mtimeNs)
    s.sha256 = known->packageSha256;
  else
    s.sha256 = digestFile(file).sha256;
  return s;
}

const LedgerEntry* StepHistory::lastSuccess() const {
  for (auto it = attempts.rbegin(); it != attempts.rend(); ++it)
    if ((*it)->succeeded()) return *it;
  return nullptr;
}

StepHistory historyOf(const Ledger& ledger, const std::string& item, const std::string& step) {
  StepHistory h;
  for (const LedgerEntry& e : ledger.entries)
    if (e.capture == item && e.step == step) h.attempts.push_back(&e);
  return h;
}

namespace {

// The latest attempt decides: a step whose last attempt failed is done again (or, for a pack
// whose package is again the one packed, recorded again), however its files compare with an
// earlier success, so that the batch and --summary (which reads each step's last attempt) agree.
bool lastFailed(const StepHistory& h, const std::string& step, std::string& why) {
  if (h.attempts.empty() || h.attempts.back()->succeeded()) return false;
  why = "its last " + step + " failed";
  return true;
}

}  // namespace

bool runStillValid(const StepHistory& run, const FileState& carrier, std::string& why) {
  if (lastFailed(run, "run", why)) return false;
  const LedgerEntry* done = run.lastSuccess();  // null only when no attempt is recorded
  if (!done) {
    why = "no run recorded";
    return false;
  }
  if (!carrier.exists) {
    why = "the carrier is gone since the run";
    return false;
  }
  if (carrier.sha256 != done->carrierSha256) {
    why = "the carrier changed since the run";
    return false;
  }
  return true;
}

bool packStillValid(const StepHistory& pack, const FileState& carrier, const FileState& package, std::string& why) {
  if (lastFailed(pack, "pack", why)) return false;
  const LedgerEntry* done = pack.lastSuccess();  // null only when no attempt is recorded
  if (!done) {
    why = "no pack recorded";
    return false;
  }
  if (!package.exists) {
    why = "the package is gone since the pack";
    return false;
  }
  if (package.sha256 != done->packageSha256) {
    why = "the package changed since the pack";
    return false;
  }
  if (!carrier.exists || carrier.sha256 != done->carrierSha256) {
    why = "the capture's carrier changed since the pack";
    return false;
  }
  return true;
}

bool verifyStillValid(const StepHistory& verify, const FileState& package, bool reexecute, std::string& why) {
  if (lastFailed(verify, "verification", why)) return false;
  // The last attempt succeeded (or there is none): without --reexecute it is the one.
  const LedgerEntry* done = nullptr;
  for (auto it = verify.attempts.rbegin(); it != verify.attempts.rend() && !done; ++it)
    if ((*it)->succeeded() && (!reexecute || (*it)->reexecuted)) done = *it;
  if (!done) {
    why = verify.attempts.empty() ? "no verification recorded" : "no re-execution recorded as sound";
    return false;
  }
  if (!package.exists) {
    why = "the package is gone";
    return false;
  }
  if (package.sha256 != done->packageSha256) {
    why = "the package changed since it was verified";
    return false;
  }
  return true;
}

std::vector<std::size_t> drawSample(std::size_t total, std::size_t count, std::uint64_t seed) {
  std::vector<std::size_t> all(total);
  std::iota(all.begin(), all.end(), std::size_t{0});
  if (count >= total) return all;
  std::mt19937_64 random(seed);
  // Fisher-Yates on the first `count` places; the bound by rejection, so that the draw is the
  // same with every standard library (std::uniform_int_distribution's algorithm is not fixed).
  for (std::size_t i = 0; i < count; ++i) {
    const std::uint64_t range = total - i;
    const std::uint64_t limit = std::numeric_limits<std::uint64_t>::max() - std::numeric_limits<std::uint64_t>::max() % range;
    std::uint64_t r;
    do r = random();
    while (r >= limit);
    std::swap(all[i], all[i + static_cast<std::size_t>(r % range)]);
  }
  all.resize(count);
  std::sort(all.begin(), all.end());
  return all;
}

}  // namespace surrogate::batch

namespace surrogate::batch {

std::vector<std::size_t> notYetVerified(const std::vector<std::string>& items, const Ledger& ledger, bool reexecute) {
  std::set<std::string> verified;
  for (const LedgerEntry& e : ledger.entries)
    if (e.step == "verify" && e.succeeded() && (!reexecute || e.reexecuted)) verified.insert(e.capture);
  std::vector<std::size_t> out;
  for (std::size_t i = 0; i < items.size(); ++i)
    if (!verified.count(items[i])) out.push_back(i);
  return out;
}

}  // namespace surrogate::batch
