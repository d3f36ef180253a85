// Test support: a deterministic mini fuzzer for the readers. Each mutation of a valid file
// must either parse (into a valid object) or throw surrogate::Error; anything else (a crash,
// another exception type, an out-of-bounds read under ASan) fails the test.
#pragma once

#include <cstdint>
#include <functional>
#include <random>
#include <string>

#include "core/error.h"

namespace surrogate::test {

using Parser = std::function<void(const std::uint8_t*, std::size_t)>;

// Runs the parser on data; returns true if it parsed, false if it threw surrogate::Error.
inline bool parsesOrThrowsError(const Parser& parse, const std::string& data) {
  try {
    parse(reinterpret_cast<const std::uint8_t*>(data.data()), data.size());
    return true;
  } catch (const surrogate::Error&) {
    return false;
  }
}

// `count` mutations of `valid` (byte flips, digit changes, insertions, deletions), half of
// them aimed at the first `headerBytes` bytes where the parser makes decisions.
inline int fuzz(const Parser& parse, const std::string& valid, std::size_t headerBytes, int count,
                unsigned seed) {
  std::mt19937 rng(seed);
  int parsed = 0;
  for (int m = 0; m < count; ++m) {
    std::string d = valid;
    const int edits = 1 + static_cast<int>(rng() % 3);
    for (int e = 0; e < edits && !d.empty(); ++e) {
      const std::size_t limit = (rng() % 2 && headerBytes < d.size()) ? headerBytes : d.size();
      const std::size_t pos = rng() % limit;
      switch (rng() % 5) {
        case 0: d[pos] = static_cast<char>(d[pos] ^ (1u << (rng() % 8))); break;
        case 1: d[pos] = static_cast<char>('0' + rng() % 10); break;
        case 2: d.insert(pos, 1, static_cast<char>(rng() % 256)); break;
        case 3: d.erase(pos, 1 + rng() % 4); break;
        default: d[pos] = "9 \n-.#e"[rng() % 7]; break;
      }
    }
    parsed += parsesOrThrowsError(parse, d) ? 1 : 0;
  }
  return parsed;
}

}  // namespace surrogate::test
