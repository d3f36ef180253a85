// What fresh memory costs on this machine, the way the pipeline takes it (core/resident.h):
// a block the size of the decoded stack of 36 x 3000x2000 (648 MB) mapped, backed by one of
//   plain      nothing: each 4 KiB page backed when first written, by a fault
//   populate   madvise(MADV_POPULATE_WRITE)
//   huge       madvise(MADV_HUGEPAGE), then backed when first written
//   huge+pop   madvise(MADV_HUGEPAGE) then MADV_POPULATE_WRITE (what makeResident does)
//   resident   surrogate::makeResident on a surrogate::MappedBlock (the stack's own path)
// then written in full twice with memset. Prints the seconds of each phase and how much of the
// block the kernel holds in huge pages (AnonHugePages). Each way runs in a child process of its
// own, as a run would, several rounds in turn.
//
// On the machine of docs/developer-guide.md ("Backed in huge pages"), a paravirtualised VM:
// populate 0.11-0.25 s then the first memset 0.75-0.91 s; huge+pop 0.05-0.14 s in all.
//
//   fresh_memory_bench [--megabytes N] [--rounds N]
#include <sys/mman.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <string>

#include "core/resident.h"

#ifndef MADV_POPULATE_WRITE
#define MADV_POPULATE_WRITE 23
#endif

namespace {

double seconds(std::chrono::steady_clock::time_point from) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - from).count();
}

long anonHugeKiB() {
  std::ifstream in("/proc/self/smaps_rollup");
  std::string key;
  long value = 0;
  while (in >> key) {
    if (key == "AnonHugePages:") {
      in >> value;
      return value;
    }
  }
  return 0;
}

// One way of backing `bytes` of fresh memory, in this process: prints its line.
void measure(const std::string& way, std::size_t bytes) {
  constexpr std::size_t kHuge = std::size_t(2) << 20;
  surrogate::MappedBlock block;
  unsigned char* p = nullptr;
  const auto start = std::chrono::steady_clock::now();
  if (way == "resident") {
    block = surrogate::MappedBlock(bytes);
    p = block.data();
    surrogate::makeResident(p, bytes);
  } else {
    void* raw = ::mmap(nullptr, bytes + kHuge, PROT_READ | PROT_WRITE, MAP_PRIVATE | MAP_ANONYMOUS, -1, 0);
    if (raw == MAP_FAILED) {
      std::perror("mmap");
      std::exit(1);
    }
    p = reinterpret_cast<unsigned char*>((reinterpret_cast<std::uintptr_t>(raw) + kHuge - 1) / kHuge * kHuge);
    if (way == "huge" || way == "huge+pop") (void)::madvise(p, bytes, MADV_HUGEPAGE);
    if (way == "populate" || way == "huge+pop") (void)::madvise(p, bytes, MADV_POPULATE_WRITE);
  }
  const double backed = seconds(start);
  auto t = std::chrono::steady_clock::now();
  std::memset(p, 1, bytes);
  const double first = seconds(t);
  t = std::chrono::steady_clock::now();
  std::memset(p, 2, bytes);
  const double second = seconds(t);
  std::printf("%-9s backing %6.3f s  first write %6.3f s  second write %6.3f s  in all %6.3f s  huge pages %5ld MiB\n",
              way.c_str(), backed, first, second, backed + first, anonHugeKiB() / 1024);
  std::fflush(stdout);
}

}  // namespace

int main(int argc, char** argv) {
  std::size_t megabytes = 648;
  int rounds = 3;
  for (int i = 1; i + 1 < argc; i += 2) {
    const std::string a = argv[i];
    if (a == "--megabytes") megabytes = std::strtoul(argv[i + 1], nullptr, 10);
    else if (a == "--rounds") rounds = std::atoi(argv[i + 1]);
  }
  const std::size_t bytes = megabytes << 20;
  std::printf("fresh memory: %zu MiB, %d rounds, each way in a process of its own\n", megabytes, rounds);
  std::fflush(stdout);  // not again in every child's copy of the buffer
  for (int r = 0; r < rounds; ++r) {
    for (const char* way : {"plain", "populate", "huge", "huge+pop", "resident"}) {
      const pid_t child = ::fork();
      if (child == 0) {
        measure(way, bytes);
        std::_Exit(0);
      }
      int status = 0;
      ::waitpid(child, &status, 0);
    }
  }
  return 0;
}
