// The executable's global operator new: large blocks (decoded photographs, stacks, models,
// maps) are marked for transparent huge pages.
//
// Why: a run touches gigabytes of freshly allocated memory, and on Debian's default kernel
// setting (transparent_hugepage "madvise") each 4 KiB page of it is faulted in separately;
// page faults were the largest single cost in profiles of `run` on a 2-core virtual machine
// (figures in docs/developer-guide.md, "Benchmarks"). Blocks of at least kHugeBlockBytes get
// madvise(MADV_HUGEPAGE) over the 2 MiB-aligned part of them; the kernel then faults in 2 MiB
// at a time where it can, and falls back to 4 KiB pages where it cannot. Nothing else
// changes: the memory still comes from malloc and returns to free, and the values computed do
// not depend on the page size.
//
// Linked into the `surrogate` executable only (replacing operator new is a whole-program
// choice); tests and libraries keep the standard one.
#include <sys/mman.h>

#include <cstdint>
#include <cstdlib>
#include <new>

namespace {

constexpr std::size_t kHugePageBytes = std::size_t(2) << 20;
constexpr std::size_t kHugeBlockBytes = std::size_t(4) << 20;

void adviseHugePages(void* block, std::size_t size) {
  if (size < kHugeBlockBytes) return;
  const auto start = reinterpret_cast<std::uintptr_t>(block);
  const std::uintptr_t first = (start + kHugePageBytes - 1) & ~(kHugePageBytes - 1);
  const std::uintptr_t end = (start + size) & ~(kHugePageBytes - 1);
  // Advice only: a kernel without transparent huge pages refuses it, and nothing is lost.
  if (end > first) madvise(reinterpret_cast<void*>(first), end - first, MADV_HUGEPAGE);
}

void* allocate(std::size_t size) noexcept {
  void* block = std::malloc(size == 0 ? 1 : size);
  if (block) adviseHugePages(block, size);
  return block;
}

}  // namespace

void* operator new(std::size_t size) {
  for (;;) {
    if (void* block = allocate(size)) return block;
    std::new_handler handler = std::get_new_handler();
    if (!handler) throw std::bad_alloc();
    handler();
  }
}

void* operator new(std::size_t size, const std::nothrow_t&) noexcept {
  try {
    return operator new(size);
  } catch (...) {
    return nullptr;
  }
}

void operator delete(void* block) noexcept { std::free(block); }
void operator delete(void* block, std::size_t) noexcept { std::free(block); }
void operator delete(void* block, const std::nothrow_t&) noexcept { std::free(block); }
