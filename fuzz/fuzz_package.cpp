// libFuzzer target: the package reader (libarchive streaming, entry checks, limits) on an
// arbitrary file taken as a .tar/.zip package.
#include <unistd.h>

#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <string>

#include "archive/package_reader.h"
#include "core/error.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  // The reader takes a file name: each input is written to one scratch file, removed at exit.
  struct ScratchFile {
    std::string path;
    ScratchFile() {
      const char* tmp = std::getenv("TMPDIR");
      path = std::string(tmp && *tmp ? tmp : "/tmp") + "/surrogate-fuzz-package-" + std::to_string(::getpid());
    }
    ~ScratchFile() { std::remove(path.c_str()); }
  };
  static const ScratchFile scratch;
  const std::string& path = scratch.path;
  FILE* f = std::fopen(path.c_str(), "wb");
  if (!f) return 0;
  std::fwrite(data, 1, size, f);
  std::fclose(f);
  surrogate::archive::Limits limits;
  limits.maxEntries = 1000;
  limits.maxEntryBytes = 8 << 20;
  limits.maxTotalBytes = 32 << 20;
  limits.ratioFloorBytes = 1 << 20;
  limits.maxTagFileBytes = 1 << 20;
  try {
    surrogate::archive::readPackage(path, limits);
  } catch (const surrogate::Error&) {
    // refusing is the expected outcome for most inputs; crashing is not
  }
  return 0;
}
