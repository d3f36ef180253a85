#include "core/resident.h"

#include <cstdint>

#include <sys/mman.h>
#include <unistd.h>

#ifndef MADV_POPULATE_WRITE
#define MADV_POPULATE_WRITE 23  // Linux 5.14; older headers lack the name, older kernels refuse it
#endif

namespace surrogate {

void makeResident(void* data, std::size_t bytes) {
  // Below a megabyte the block most likely comes from memory the process already uses, and
  // the call would cost more than the faults it saves.
  if (bytes < (std::size_t(1) << 20)) return;
  static const std::uintptr_t page = static_cast<std::uintptr_t>(::sysconf(_SC_PAGESIZE));
  const std::uintptr_t begin = (reinterpret_cast<std::uintptr_t>(data) + page - 1) / page * page;
  const std::uintptr_t end = (reinterpret_cast<std::uintptr_t>(data) + bytes) / page * page;
  if (end <= begin) return;
  // EINVAL (an older kernel), ENOMEM, EFAULT: the pages are backed as they are written instead.
  (void)::madvise(reinterpret_cast<void*>(begin), end - begin, MADV_POPULATE_WRITE);
}

}  // namespace surrogate
