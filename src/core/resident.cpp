#include "core/resident.h"

#include <cstdint>
#include <new>
#include <utility>

#include <malloc.h>

#include <sys/mman.h>
#include <unistd.h>

#ifndef MADV_POPULATE_WRITE
#define MADV_POPULATE_WRITE 23  // Linux 5.14; older headers lack the name, older kernels refuse it
#endif

namespace surrogate {

namespace {
constexpr std::uintptr_t kHugePage = std::uintptr_t(2) << 20;  // x86-64's transparent huge page
}

void makeResident(void* data, std::size_t bytes) {
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
  if (hugeEnd > hugeBegin) (void)::madvise(reinterpret_cast<void*>(hugeBegin), hugeEnd - hugeBegin, MADV_HUGEPAGE);
  // EINVAL (an older kernel), ENOMEM, EFAULT: the pages are backed as they are written instead.
  (void)::madvise(reinterpret_cast<void*>(begin), end - begin, MADV_POPULATE_WRITE);
}

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
