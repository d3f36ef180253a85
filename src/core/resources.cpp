#include "core/resources.h"

#include <unistd.h>

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
}  // namespace

fs::path resourcePath(const std::string& relative) {
  std::vector<fs::path> roots;
  if (const char* env = std::getenv("SURROGATE_RESOURCES"); env && *env) roots.emplace_back(env);
  if (const fs::path dir = executableDir(); !dir.empty())
    roots.push_back(dir.parent_path() / "share" / "surrogate");
  roots.emplace_back(SURROGATE_RESOURCE_DIR);
  for (const fs::path& root : roots) {
    const fs::path candidate = root / relative;
    if (fs::exists(candidate)) return candidate;
  }
  throw Error(ErrorKind::Internal, relative, "installation",
              "a data file of Surrogate is missing (looked in $SURROGATE_RESOURCES, "
              "share/surrogate next to the program and the source tree); reinstall Surrogate");
}

}  // namespace surrogate
