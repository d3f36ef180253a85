// Packing throughput: a capture-sized payload (default 60 images of 25 MB, raw-sized files of
// pseudo-random bytes) packed as a folder, a .tar and a .zip, against the physical floor of
// reading and hashing the same files: `sha512sum` alone, and `sha256sum` then `sha512sum`.
// Target (issue 5): packing <= 1.1x the time of `sha512sum` alone. All runs read from the page
// cache (the files were just written), so the comparison is of CPU work, not of the disk.
//
//   pack_bench [--images N] [--mb MB] [--runs R] [--dir DIR] [--out DIR]
//
// --out puts the packages elsewhere than the payload (e.g. /dev/shm, to take the disk's write
// speed out of the figure: sha512sum only reads, packing also writes every byte).
#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <thread>
#include <string>
#include <vector>

#include "archive/bag.h"

namespace fs = std::filesystem;
using namespace surrogate;

namespace {

double seconds(const std::chrono::steady_clock::time_point& t0) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
}

template <typename F>
double best(int runs, F f) {
  std::vector<double> t;
  for (int i = 0; i < runs; ++i) {
    const auto t0 = std::chrono::steady_clock::now();
    f();
    t.push_back(seconds(t0));
  }
  return *std::min_element(t.begin(), t.end());
}

void writeRandomFile(const fs::path& p, std::size_t bytes, std::uint64_t seed) {
  std::vector<std::uint64_t> block(1 << 17);  // 1 MiB
  std::uint64_t x = seed * 0x9E3779B97F4A7C15ULL + 1;
  std::ofstream f(p, std::ios::binary);
  for (std::size_t done = 0; done < bytes;) {
    for (std::uint64_t& v : block) {  // xorshift64*: incompressible, fast
      x ^= x >> 12;
      x ^= x << 25;
      x ^= x >> 27;
      v = x * 0x2545F4914F6CDD1DULL;
    }
    const std::size_t n = std::min(bytes - done, block.size() * sizeof(std::uint64_t));
    f.write(reinterpret_cast<const char*>(block.data()), static_cast<std::streamsize>(n));
    done += n;
  }
}

int shell(const std::string& command) { return std::system(command.c_str()); }

}  // namespace

int main(int argc, char** argv) {
  int images = 60, mb = 25, runs = 3;
  fs::path dir = fs::temp_directory_path() / "surrogate-pack-bench";
  fs::path outDir;
  for (int i = 1; i + 1 < argc; i += 2) {
    const std::string a = argv[i];
    if (a == "--images") images = std::atoi(argv[i + 1]);
    else if (a == "--mb") mb = std::atoi(argv[i + 1]);
    else if (a == "--runs") runs = std::atoi(argv[i + 1]);
    else if (a == "--dir") dir = argv[i + 1];
    else if (a == "--out") outDir = argv[i + 1];
    else {
      std::fprintf(stderr, "usage: pack_bench [--images N] [--mb MB] [--runs R] [--dir DIR] [--out DIR]\n");
      return 2;
    }
  }
  fs::remove_all(dir);
  if (outDir.empty()) outDir = dir;
  fs::create_directories(outDir);
  const fs::path capture = dir / "capture" / "original-captures";
  fs::create_directories(capture);
  archive::BagInput in;
  std::string fileList;
  for (int i = 0; i < images; ++i) {
    char name[32];
    std::snprintf(name, sizeof name, "IMG_%04d.dng", i + 1);
    writeRandomFile(capture / name, static_cast<std::size_t>(mb) * 1000 * 1000, static_cast<std::uint64_t>(i + 1));
    in.payload.push_back({std::string("data/original-captures/") + name, capture / name, ""});
    fileList += " '" + (capture / name).string() + "'";
  }
  const double totalMb = static_cast<double>(images) * mb;
  std::printf("payload: %d files of %d MB (%.0f MB), best of %d runs, hardware threads %u\n", images, mb,
              totalMb, runs, std::thread::hardware_concurrency());
  std::printf("packages written to %s\n", outDir.c_str());

  // Warm the cache, then the floors.
  shell("cat" + fileList + " > /dev/null");
  const double t512 = best(runs, [&] { shell("sha512sum" + fileList + " > /dev/null"); });
  const double t256 = best(runs, [&] { shell("sha256sum" + fileList + " > /dev/null"); });
  std::printf("%-28s %8.2f s %9.1f MB/s\n", "sha512sum", t512, totalMb / t512);
  std::printf("%-28s %8.2f s %9.1f MB/s\n", "sha256sum + sha512sum", t256 + t512, totalMb / (t256 + t512));

  for (const char* name : {"bag", "bag.tar", "bag.zip"}) {
    const fs::path out = outDir / name;
    const double t = best(runs, [&] {
      fs::remove_all(out);
      archive::writeBag(in, out);
    });
    char label[64];
    std::snprintf(label, sizeof label, "pack (%s)", archive::bagFormatName(archive::bagFormatFor(out)));
    std::printf("%-28s %8.2f s %9.1f MB/s   %.2fx sha512sum, %.2fx sha256sum+sha512sum\n", label, t,
                totalMb / t, t / t512, t / (t256 + t512));
    fs::remove_all(out);
  }
  fs::remove_all(dir);
  return 0;
}
