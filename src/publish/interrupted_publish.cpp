#include "publish/interrupted_publish.h"

#include <signal.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <cstdlib>
#include <utility>

#include "core/temp_dir.h"

namespace surrogate::publish {

namespace fs = std::filesystem;

namespace {
const char* const kPartial = ".partial-";
// mkdtemp replaces the six X of the pattern with letters and digits.
constexpr std::size_t kRandomChars = 6;
// A process id has at most 7 digits on Linux (pid_max is at most 2^22).
constexpr std::size_t kMaxPidDigits = 9;

fs::path parentOf(const fs::path& out) { return out.parent_path().empty() ? fs::path(".") : out.parent_path(); }

bool allDigits(const std::string& s) {
  if (s.empty()) return false;
  for (char c : s)
    if (c < '0' || c > '9') return false;
  return true;
}

bool alphanumeric(const std::string& s) {
  for (char c : s)
    if (!((c >= '0' && c <= '9') || (c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z'))) return false;
  return true;
}

// The writer's process id when `name` is ".NAME.partial-PID-XXXXXX"; 0 for any other name.
pid_t writerOf(const std::string& name) {
  if (name.size() < 2 || name[0] != '.') return 0;
  const std::size_t at = name.rfind(kPartial);
  if (at == std::string::npos || at < 2) return 0;
  const std::string rest = name.substr(at + std::string(kPartial).size());  // "PID-XXXXXX"
  const std::size_t dash = rest.find('-');
  if (dash == std::string::npos || dash > kMaxPidDigits || rest.size() != dash + 1 + kRandomChars) return 0;
  const std::string pid = rest.substr(0, dash);
  if (!allDigits(pid) || !alphanumeric(rest.substr(dash + 1))) return 0;
  return static_cast<pid_t>(std::strtol(pid.c_str(), nullptr, 10));
}

// Only "no such process" means the writer is gone: a running process (even another user's,
// EPERM) or a process id reused since keeps its folder; this process's own folders are never
// leftovers.
bool writerIsGone(pid_t pid) { return pid > 0 && pid != ::getpid() && ::kill(pid, 0) != 0 && errno == ESRCH; }

// A real folder (not a link to one) that belongs to this user: nothing else is ours to remove.
bool ownFolder(const fs::path& p) {
  struct stat st {};
  return ::lstat(p.c_str(), &st) == 0 && S_ISDIR(st.st_mode) && st.st_uid == ::geteuid();
}
}  // namespace

std::string stagingPattern(const fs::path& out) {
  return (parentOf(out) / ("." + out.filename().string() + kPartial + std::to_string(::getpid()) + "-XXXXXX"))
      .string();
}

std::vector<std::string> removeInterruptedPublishes(const fs::path& out) {
  std::vector<std::pair<fs::path, pid_t>> leftovers;  // listed first: nothing is removed mid-listing
  std::error_code ec;
  for (fs::directory_iterator it(parentOf(out), ec), end; !ec && it != end; it.increment(ec)) {
    const pid_t pid = writerOf(it->path().filename().string());
    if (writerIsGone(pid) && ownFolder(it->path())) leftovers.emplace_back(it->path(), pid);
  }
  std::vector<std::string> removed;
  for (const auto& [path, pid] : leftovers) {
    // removeTreeForcibly empties read-only folders too and never follows a link inside.
    if (!removeTreeForcibly(path.c_str())) continue;
    removed.push_back("removed " + path.string() + ", the partial folder of a publish that did not finish "
                      "(process " + std::to_string(pid) + " no longer runs)");
  }
  return removed;
}

}  // namespace surrogate::publish
