// Fresh memory made resident before it is written.
//
// A large block from malloc is mapped but not backed: each 4 KiB page is backed when it is first
// written, by a page fault. On the virtual machines this project runs on a fault is costly
// (measured: writing one byte a page into 648 MB of fresh memory, 1.9-2.4 s on one thread),
// and backing the same range in one madvise(MADV_POPULATE_WRITE) call took 0.9-1.1 s
// (docs/developer-guide.md, "Fresh memory").
#pragma once

#include <cstddef>

namespace surrogate {

// Backs the whole pages inside [data, data + bytes) now, as writing them would; the bytes are
// unchanged (zero where never written). Best effort: on a kernel without MADV_POPULATE_WRITE
// (Linux before 5.14) or when memory is short it does nothing, and the pages are backed as
// they are written. Worth calling only for blocks of megabytes about to be written in full.
void makeResident(void* data, std::size_t bytes);

// c.resize(n) (a std::vector or std::string of bytes or numbers) with the memory of the new
// elements backed first: for a large container about to be written in full.
template <class Container>
void resizeResident(Container& c, std::size_t n) {
  if (n > c.size()) {
    c.reserve(n);
    makeResident(c.data() + c.size(), (n - c.size()) * sizeof(*c.data()));
  }
  c.resize(n);
}

// c.reserve(n) with the memory reserved past c.size() backed first: for a large container
// about to be appended to up to that size.
template <class Container>
void reserveResident(Container& c, std::size_t n) {
  c.reserve(n);
  makeResident(c.data() + c.size(), (c.capacity() - c.size()) * sizeof(*c.data()));
}

}  // namespace surrogate
