#include "core/resident.h"

#include <algorithm>
#include <atomic>
#include <cstdint>
#include <new>
#include <system_error>
#include <thread>
#include <utility>
#include <vector>

#include <malloc.h>


#include <sys/mman.h>
#include <unistd.h>

#ifndef MADV_POPULATE_WRITE
#define MADV_POPULATE_WRITE 23  // Linux 5.14; older headers lack the name, older kernels refuse it
#endif

namespace surrogate {

namespace {
constexpr std::uintptr_t kHugePage = std::uintptr_t(2) << 20;  // x86-64's transparent huge page
// The fewest huge pages (8 MiB) worth another thread in makeResident: starting one costs about
// as much as backing a fresh huge page, and memory that is already backed (freed and reused)
// is walked at tens of gigabytes a second.
constexpr std::size_t kMinHugePagesPerThread = 4;

// makeResident, advising the whole huge pages as such first or (makeResidentAdvised) not.
void backResident(void* data, std::size_t bytes, int threads, bool advise) {
  // Below a megabyte the block most likely comes from memory the process already uses, and
  // the call would cost more than the faults it saves.
  if (bytes < (std::size_t(1) << 20)) return;
  static const std::uintptr_t page = static_cast<std::uintptr_t>(::sysconf(_SC_PAGESIZE));
  const std::uintptr_t at = reinterpret_cast<std::uintptr_t>(data);
  const std::uintptr_t begin = (at + page - 1) / page * page;
  const std::uintptr_t end = (at + bytes) / page * page;
  if (end <= begin) return;
  // The whole huge pages inside the block backed as such: populating them is a handful of
  // faults, where 4 KiB pages each cost one when first written even after populating
  // (docs/developer-guide.md, "Fresh memory"). Refused (a kernel without transparent huge
  // pages, or with them set to "never"): 4 KiB pages, as before.
  const std::uintptr_t hugeBegin = (at + kHugePage - 1) / kHugePage * kHugePage;
  const std::uintptr_t hugeEnd = (at + bytes) / kHugePage * kHugePage;
  if (advise && hugeEnd > hugeBegin)
    (void)::madvise(reinterpret_cast<void*>(hugeBegin), hugeEnd - hugeBegin, MADV_HUGEPAGE);
  // EINVAL (an older kernel), ENOMEM, EFAULT: the pages are backed as they are written instead.
  const auto populate = [](std::uintptr_t from, std::uintptr_t to) {
    if (to > from) (void)::madvise(reinterpret_cast<void*>(from), to - from, MADV_POPULATE_WRITE);
  };
  // Backing fresh memory is clearing pages, here and on the host, and two vCPUs do it at once:
  // 46 MB took 110 CPU-ms on one thread, 55-65 on each of two (halves). Which pages are fresh
  // is not known (a block often starts in memory freed before and ends in fresh), so rather
  // than fixed parts, each thread takes the next huge page until none is left (no huge page
  // split between two threads); the caller, the bits before and after the whole huge pages.
  // On threads of their own: parallelFor may hand all of it to one worker.
  const std::size_t hugePages = hugeEnd > hugeBegin ? (hugeEnd - hugeBegin) / kHugePage : 0;
  const std::size_t helpers =
      std::min<std::size_t>(threads > 1 ? static_cast<std::size_t>(threads - 1) : 0, hugePages / kMinHugePagesPerThread);
  if (helpers == 0) {
    populate(begin, end);
    return;
  }
  std::atomic<std::size_t> next{0};
  const auto share = [&] {
    for (std::size_t k; (k = next.fetch_add(1, std::memory_order_relaxed)) < hugePages;)
      populate(hugeBegin + k * kHugePage, hugeBegin + (k + 1) * kHugePage);
  };
  std::vector<std::thread> others;
  for (std::size_t t = 0; t < helpers; ++t) {
    try {
      others.emplace_back(share);
    } catch (const std::system_error&) {  // no thread to be had: the others share the pages
      break;
    }
  }
  populate(begin, hugeBegin);
  populate(hugeEnd, end);
  share();
  for (std::thread& t : others) t.join();
}
}  // namespace

void makeResident(void* data, std::size_t bytes, int threads) { backResident(data, bytes, threads, true); }

void makeResidentAdvised(void* data, std::size_t bytes, int threads) { backResident(data, bytes, threads, false); }

void reuseFreedMemory() {
  ::mallopt(M_MMAP_MAX, 0);
  ::mallopt(M_TRIM_THRESHOLD, INT32_MAX);
}

MappedBlock::MappedBlock(std::size_t bytes) : bytes_(bytes) {
  if (bytes == 0) return;
  // Mapped with a huge page's slack and cut to whole huge pages on a huge page boundary, all
  // of it advised as huge pages now. A caller backs it in parts (the stack: an image's slot at
  // a time, from the thread decoding it), and a part rarely holds whole huge pages of its own:
  // advised part by part, most of a 2.9 MB slot stayed in 4 KiB pages, and decoding 36 JPEGs
  // of 1200x800 into their slots took 0.30 CPU-s against 0.13 for the block advised at once
  // (docs/developer-guide.md, "Backed in huge pages").
  mapped_ = (bytes + kHugePage - 1) / kHugePage * kHugePage;
  const std::size_t slack = kHugePage;
  void* p = ::mmap(nullptr, mapped_ + slack, PROT_READ | PROT_WRITE, MAP_PRIVATE | MAP_ANONYMOUS, -1, 0);
  if (p == MAP_FAILED) throw std::bad_alloc();
  const std::uintptr_t at = reinterpret_cast<std::uintptr_t>(p);
  const std::uintptr_t aligned = (at + kHugePage - 1) / kHugePage * kHugePage;
  if (aligned > at) ::munmap(p, aligned - at);
  if (const std::size_t tail = at + mapped_ + slack - (aligned + mapped_); tail > 0)
    ::munmap(reinterpret_cast<void*>(aligned + mapped_), tail);
  data_ = reinterpret_cast<std::uint8_t*>(aligned);
  // Refused (no transparent huge pages): 4 KiB pages, as makeResident says.
  (void)::madvise(data_, mapped_, MADV_HUGEPAGE);
}

MappedBlock::~MappedBlock() {
  if (data_) ::munmap(data_, mapped_);
}

MappedBlock::MappedBlock(MappedBlock&& other) noexcept
    : data_(std::exchange(other.data_, nullptr)),
      bytes_(std::exchange(other.bytes_, 0)),
      mapped_(std::exchange(other.mapped_, 0)) {}

MappedBlock& MappedBlock::operator=(MappedBlock&& other) noexcept {
  if (this != &other) {
    if (data_) ::munmap(data_, mapped_);
    data_ = std::exchange(other.data_, nullptr);
    bytes_ = std::exchange(other.bytes_, 0);
    mapped_ = std::exchange(other.mapped_, 0);
  }
  return *this;
}

}  // namespace surrogate
