#include "core/resources.h"

#include <atomic>
#include <cstdlib>
#include <vector>

#include "core/error.h"

namespace surrogate {

namespace fs = std::filesystem;

namespace {

fs::path executableDir() {
  std::error_code ec;
  const fs::path exe = fs::read_symlink("/proc/self/exe", ec);
  return ec ? fs::path() : exe.parent_path();
}

// `inner` lies within `outer` (or is it): compared as written, both absolute.
bool within(const fs::path& inner, const fs::path& outer) {
  const fs::path relative = inner.lexically_relative(outer);
  return !relative.empty() && *relative.begin() != "..";
}

struct DataFolder {
  fs::path root;           // empty: none found
  std::string lookedIn;    // the folders tried, for the message
};

DataFolder chooseDataFolder() {
  DataFolder out;
  std::vector<fs::path> candidates;
  const fs::path exeDir = executableDir();
  if (!exeDir.empty()) candidates.push_back(exeDir.parent_path() / "share" / "surrogate");
  if (!exeDir.empty() && within(exeDir, SURROGATE_BUILD_DIR)) candidates.emplace_back(SURROGATE_SOURCE_TREE);
  candidates.emplace_back(SURROGATE_INSTALL_DATA_DIR);
  for (const fs::path& c : candidates) {
    out.lookedIn += (out.lookedIn.empty() ? "" : ", ") + c.string();
    std::error_code ec;
    if (out.root.empty() && fs::is_directory(c, ec)) out.root = c;
  }
  return out;
}

const DataFolder& dataFolder() {
  static const DataFolder folder = chooseDataFolder();
  return folder;
}

// The message names the file itself ("reinstall Surrogate: FILE is missing"), so the error's file
// is left empty: said once, the remedy first.
[[noreturn]] void missing(const fs::path& root, const std::string& relative) {
  throw Error(ErrorKind::Input, "", "installation",
              "reinstall Surrogate: " + (root / relative).string() +
                  " is missing (Surrogate reads its schemas, stylesheets and mapping tables from " +
                  root.string() + "; the package or build it came from is incomplete)");
}

}  // namespace

fs::path requireDataFiles() {
  static std::atomic<bool> complete{false};  // checked once found complete; a file gone later is
                                             // still named by resourcePath
  const DataFolder& folder = dataFolder();
  if (complete.load()) return folder.root;
  if (folder.root.empty())
    throw Error(ErrorKind::Input, "", "installation",
                "reinstall Surrogate: its data folder is missing (looked in " + folder.lookedIn +
                    "; Surrogate reads its schemas, stylesheets and mapping tables from there)");
  for (const std::string& rel : dataFileNames()) {
    std::error_code ec;
    if (!fs::is_regular_file(folder.root / rel, ec)) missing(folder.root, rel);
  }
  complete.store(true);
  return folder.root;
}

fs::path resourcePath(const std::string& relative) {
  if (const char* env = std::getenv("SURROGATE_RESOURCES"); env && *env) {
    const fs::path candidate = fs::path(env) / relative;
    std::error_code ec;
    if (fs::exists(candidate, ec)) return candidate;
  }
  const fs::path root = requireDataFiles();
  std::error_code ec;
  if (!fs::exists(root / relative, ec)) missing(root, relative);
  return root / relative;
}

}  // namespace surrogate
