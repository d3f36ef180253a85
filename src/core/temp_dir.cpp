#include "core/temp_dir.h"

#include <stdlib.h>

#include <cerrno>
#include <cstdlib>
#include <cstring>

#include "core/error.h"

namespace surrogate {

namespace fs = std::filesystem;

TempDir::TempDir(const std::string& purpose) {
  const char* base = std::getenv("TMPDIR");
  std::string pattern = std::string(base && *base ? base : "/tmp") + "/surrogate-" + purpose + "-XXXXXX";
  if (!::mkdtemp(pattern.data()))
    throw Error(ErrorKind::Internal, pattern, purpose,
                std::string("cannot create a temporary folder (") + std::strerror(errno) +
                    "); set TMPDIR to a writable folder with room for the package");
  path_ = pattern;
}

TempDir::~TempDir() {
  std::error_code ec;
  // Folders made read-only (the verifier's replay copy) must be writable again to be emptied.
  for (fs::recursive_directory_iterator it(path_, ec), end; !ec && it != end; it.increment(ec))
    if (it->is_directory(ec) && !it->is_symlink(ec))
      fs::permissions(it->path(), fs::perms::owner_all, fs::perm_options::add, ec);
  fs::remove_all(path_, ec);
}

}  // namespace surrogate
