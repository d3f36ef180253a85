// Fresh memory made resident (core/resident.h): the kernel's own account of which pages are
// backed (mincore) before and after, and the bytes left as they were.
#include <catch2/catch.hpp>

#include <sys/mman.h>
#include <sys/utsname.h>
#include <unistd.h>

#include <cerrno>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <string>
#include <utility>
#include <vector>

#include "core/resident.h"

using namespace surrogate;

namespace {

const std::size_t kPage = static_cast<std::size_t>(::sysconf(_SC_PAGESIZE));

// Pages of [p, p + bytes) (page-aligned p) the kernel says are in memory.
std::size_t residentPages(void* p, std::size_t bytes) {
  std::vector<unsigned char> in((bytes + kPage - 1) / kPage);
  REQUIRE(::mincore(p, bytes, in.data()) == 0);
  std::size_t n = 0;
  for (unsigned char c : in) n += c & 1;
  return n;
}

// The whole pages inside [p, p + bytes).
std::pair<void*, std::size_t> wholePages(void* p, std::size_t bytes) {
  const std::uintptr_t begin = (reinterpret_cast<std::uintptr_t>(p) + kPage - 1) / kPage * kPage;
  const std::uintptr_t end = (reinterpret_cast<std::uintptr_t>(p) + bytes) / kPage * kPage;
  return {reinterpret_cast<void*>(begin), end - begin};
}

// MADV_POPULATE_WRITE came with Linux 5.14; before it makeResident does nothing.
bool kernelPopulates() {
  utsname u{};
  if (::uname(&u) != 0) return false;
  int major = 0, minor = 0;
  if (std::sscanf(u.release, "%d.%d", &major, &minor) != 2) return false;
  return major > 5 || (major == 5 && minor >= 14);
}

// A fresh anonymous mapping: no page backed until touched. Never in huge pages, which would
// back the neighbours of a touched page too (where transparent huge pages are "always").
struct Mapping {
  std::size_t bytes;
  void* p;
  explicit Mapping(std::size_t n) : bytes(n), p(::mmap(nullptr, n, PROT_READ | PROT_WRITE, MAP_PRIVATE | MAP_ANONYMOUS, -1, 0)) {
    REQUIRE(p != MAP_FAILED);
    ::madvise(p, n, MADV_NOHUGEPAGE);
  }
  ~Mapping() { ::munmap(p, bytes); }
  std::uint8_t* bytesAt(std::size_t offset) const { return static_cast<std::uint8_t*>(p) + offset; }
};

}  // namespace

TEST_CASE("makeResident backs every whole page of the range, and no page outside it") {
  const std::size_t pages = 1024;  // 4 MiB of 4 KiB pages
  Mapping m(pages * kPage);
  REQUIRE(residentPages(m.p, m.bytes) == 0);
  // From the middle of page 10 to the middle of page 1000: pages 11..999 are whole.
  makeResident(m.bytesAt(10 * kPage + kPage / 2), 990 * kPage);
  if (!kernelPopulates()) {
    CHECK(residentPages(m.p, m.bytes) == 0);
    return;
  }
  CHECK(residentPages(m.bytesAt(11 * kPage), 989 * kPage) == 989);
  CHECK(residentPages(m.p, 11 * kPage) == 0);
  CHECK(residentPages(m.bytesAt(1000 * kPage), 24 * kPage) == 0);
}

TEST_CASE("makeResidentAdvised backs a range as makeResident does, leaving its advice as it was") {
  const std::size_t pages = 2048;  // 8 MiB: a whole huge page inside the range wherever it lies
  Mapping m(pages * kPage);  // advised against huge pages: makeResident would advise them
  m.bytesAt(100 * kPage)[7] = 42;
  makeResidentAdvised(m.bytesAt(10 * kPage + kPage / 2), 1990 * kPage, 2);
  if (kernelPopulates()) {
    CHECK(residentPages(m.bytesAt(11 * kPage), 1989 * kPage) == 1989);
    CHECK(residentPages(m.p, 11 * kPage) == 0);
    CHECK(residentPages(m.bytesAt(2000 * kPage), 48 * kPage) == 0);
  }
  CHECK(m.bytesAt(100 * kPage)[7] == 42);
  CHECK(m.bytesAt(500 * kPage)[0] == 0);
  // The mapping's own advice stands: the smaps entry of the whole huge page inside the range
  // (which makeResident advises) still says nohugepage ("nh").
  const std::uintptr_t huge = std::uintptr_t(2) << 20;
  const std::uintptr_t at = (reinterpret_cast<std::uintptr_t>(m.bytesAt(10 * kPage + kPage / 2)) + huge - 1) / huge * huge + huge / 2;
  REQUIRE(at + huge / 2 <= reinterpret_cast<std::uintptr_t>(m.bytesAt(2000 * kPage)));
  FILE* f = std::fopen("/proc/self/smaps", "r");
  REQUIRE(f != nullptr);
  char line[512];
  bool inside = false, advisedAgainst = false;
  while (std::fgets(line, sizeof line, f)) {
    unsigned long from = 0, to = 0;
    if (std::sscanf(line, "%lx-%lx ", &from, &to) == 2) inside = from <= at && at < to;
    if (inside && std::string(line).rfind("VmFlags:", 0) == 0) advisedAgainst = std::string(line).find(" nh") != std::string::npos;
  }
  std::fclose(f);
  CHECK(advisedAgainst);
}

TEST_CASE("makeResident leaves what is written as it was, and fresh pages zero") {
  const std::size_t pages = 512;
  Mapping m(pages * kPage);
  for (std::size_t k = 0; k < pages; k += 3) *m.bytesAt(k * kPage + 7) = static_cast<std::uint8_t>(k + 1);
  makeResident(m.p, m.bytes);
  for (std::size_t k = 0; k < pages; ++k) {
    INFO("page " << k);
    CHECK(*m.bytesAt(k * kPage + 7) == (k % 3 == 0 ? static_cast<std::uint8_t>(k + 1) : 0));
    CHECK(*m.bytesAt(k * kPage) == 0);
  }
}

TEST_CASE("makeResident leaves a range under a megabyte to be backed as it is written") {
  Mapping m(256 * kPage);  // 1 MiB: the range below is 255 pages
  makeResident(m.bytesAt(kPage), 255 * kPage - 1);
  CHECK(residentPages(m.p, m.bytes) == 0);
}

TEST_CASE("resizeResident and reserveResident are resize and reserve: content and size") {
  std::vector<std::uint16_t> v = {1, 2, 3};
  resizeResident(v, 3'000'000);  // 6 MB
  REQUIRE(v.size() == 3'000'000);
  CHECK(v[0] == 1);
  CHECK(v[2] == 3);
  std::size_t nonZero = 0;
  for (std::size_t i = 3; i < v.size(); ++i) nonZero += v[i] != 0;
  CHECK(nonZero == 0);
  resizeResident(v, 2);  // shrinking as resize does
  CHECK(v == std::vector<std::uint16_t>{1, 2});

  std::string s = "head";
  reserveResident(s, 5'000'000);
  CHECK(s == "head");
  CHECK(s.capacity() >= 5'000'000);
  s.append(4'999'996, 'x');
  CHECK(s.size() == 5'000'000);
  CHECK(s.compare(0, 5, "headx") == 0);
}

namespace {
// The share of a freshly allocated block's pages that are already backed, after a block of the
// same size was allocated, written in full and freed.
double backedShareAfterFreeing(std::size_t bytes) {
  void* a = std::malloc(bytes);
  REQUIRE(a != nullptr);
  // Written a byte a page through volatile, so that the writes are not dropped as dead before
  // the free.
  for (std::size_t i = 0; i < bytes; i += kPage) static_cast<volatile char*>(a)[i] = 1;
  std::free(a);
  void* b = std::malloc(bytes);
  REQUIRE(b != nullptr);
  const auto [p, n] = wholePages(b, bytes);
  const double share = double(residentPages(p, n)) / double(n / kPage);
  std::free(b);
  return share;
}
}  // namespace

// The only test that changes malloc's policy (for the rest of its process: ctest runs each test
// case in a process of its own).
TEST_CASE("after reuseFreedMemory a large block is served again from what was freed, not mapped afresh") {
  const std::size_t bytes = 48u << 20;  // LibRaw's image buffer at 6 Mpx; above glibc's 32 MiB
  CHECK(backedShareAfterFreeing(bytes) < 0.5);  // glibc's default: a mapping of its own each time
  reuseFreedMemory();
  CHECK(backedShareAfterFreeing(bytes) == 1.0);  // the pages the freed block was written in
}

TEST_CASE("MappedBlock is a zeroed mapping of its own on a huge page boundary, given back when let go") {
  MappedBlock block(5 * kPage + 3);
  REQUIRE(block.data() != nullptr);
  CHECK(block.size() == 5 * kPage + 3);
  CHECK(reinterpret_cast<std::uintptr_t>(block.data()) % (std::uintptr_t(2) << 20) == 0);  // a huge page's boundary
  CHECK(residentPages(block.data(), 6 * kPage) == 0);
  for (std::size_t i = 0; i < block.size(); ++i) REQUIRE(block.data()[i] == 0);
  block.data()[kPage] = 7;
  // Mapped in whole huge pages (the advice covers all of it): the rest of the 2 MiB is the
  // block's own, and all of it goes when the block does.
  const std::size_t huge = std::size_t(2) << 20;
  std::vector<unsigned char> in(huge / kPage);
  CHECK(::mincore(block.data(), huge, in.data()) == 0);
  void* const at = block.data();
  {
    MappedBlock moved = std::move(block);
    CHECK(block.data() == nullptr);
    CHECK(moved.data() == at);
    CHECK(moved.data()[kPage] == 7);
  }
  errno = 0;
  CHECK(::mincore(at, huge, in.data()) == -1);
  CHECK(errno == ENOMEM);  // no longer mapped
}
