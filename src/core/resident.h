// Fresh memory: made resident before it is written, reused rather than mapped again, or a
// mapping of its own.
//
// A large block from malloc is mapped but not backed: each 4 KiB page is backed when it is first
// written, by a page fault. On the virtual machines this project runs on a fault is costly
// (measured: writing one byte a page into 648 MB of fresh memory, 1.9-2.4 s on one thread),
// and backing the same range in one madvise(MADV_POPULATE_WRITE) call took 0.9-1.1 s, most of
// it the first write to each page after it; backed in 2 MiB huge pages, 0.05-0.14 s
// (docs/developer-guide.md, "Fresh memory", "Backed in huge pages").
#pragma once

#include <cstddef>
#include <cstdint>

namespace surrogate {

// Backs the whole pages inside [data, data + bytes) now, as writing them would, in
// transparent huge pages where whole ones fit; the bytes are unchanged (zero where never
// written). Best effort: on a kernel without MADV_POPULATE_WRITE (Linux before 5.14) or when
// memory is short it does nothing, and the pages are backed as they are written; without
// transparent huge pages, in 4 KiB pages. Worth calling only for blocks of megabytes about to
// be written in full. With `threads` above 1, the huge pages of a block of 8 MiB or more are
// shared among that many threads, backed at once: clearing fresh pages is most of the cost
// (the hsh2 fit's 46 MB of kept coefficients at 36 x 1200x800: 30-70 ms of one core while
// the other waited).
void makeResident(void* data, std::size_t bytes, int threads = 1);

// makeResident for memory already advised as huge pages (a MappedBlock's): the same backing
// without advising again. madvise(MADV_HUGEPAGE) takes the process's memory map for writing,
// even when nothing changes, and so waits for every other thread's backing or page fault in
// progress and holds up those that follow: two threads decoding into one MappedBlock's slots
// spent a fifth of their time waiting on each other.
void makeResidentAdvised(void* data, std::size_t bytes, int threads = 1);

// c.resize(n) (a std::vector or std::string of bytes or numbers) with the memory of the new
// elements backed first: for a large container about to be written in full. `threads` as for
// makeResident.
template <class Container>
void resizeResident(Container& c, std::size_t n, int threads = 1) {
  if (n > c.size()) {
    c.reserve(n);
    makeResident(c.data() + c.size(), (n - c.size()) * sizeof(*c.data()), threads);
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

// From now on, for the rest of the process, malloc serves large blocks from memory the process
// has freed rather than from fresh mappings, and keeps what is freed for the next request
// (glibc: M_MMAP_MAX 0, a trim threshold no block reaches). The pipeline allocates and frees
// the same large blocks over and over: LibRaw's buffers for every camera raw image (about 10
// bytes a pixel: 60 MB at 6 Mpx), each fit's coefficient planes and model, each derived
// picture and its PNG stream. By default glibc maps every block of 32 MiB or more afresh and
// unmaps it when freed, so each is fresh memory backed page by page again. The cost: memory
// freed stays with the process (its peak is unchanged, since a freed block is what the next
// one reuses). For a program's main, before any thread starts; the CLI calls it for every
// command.
void reuseFreedMemory();

// A block of fresh memory of its own mapping, whatever malloc's policy: for the decoded stack,
// held for most of a run and given back to the system as soon as it is let go. Whole 2 MiB
// huge pages from a 2 MiB boundary, advised as such at once, so that makeResident (or a write)
// backs any part of it in huge pages. Uninitialised (zero until written). Throws
// std::bad_alloc when the system refuses it.
class MappedBlock {
 public:
  MappedBlock() = default;
  explicit MappedBlock(std::size_t bytes);
  ~MappedBlock();
  MappedBlock(MappedBlock&& other) noexcept;
  MappedBlock& operator=(MappedBlock&& other) noexcept;
  MappedBlock(const MappedBlock&) = delete;
  MappedBlock& operator=(const MappedBlock&) = delete;
  std::uint8_t* data() const { return data_; }
  std::size_t size() const { return bytes_; }

 private:
  std::uint8_t* data_ = nullptr;
  std::size_t bytes_ = 0;
  std::size_t mapped_ = 0;  // bytes_ rounded up to whole huge pages
};

}  // namespace surrogate
