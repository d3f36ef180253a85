// Batcher's merge-exchange sort (Knuth, The Art of Computer Programming, 5.2.2, Algorithm M) as
// its list of compare-exchanges: a sorting network, the same fixed sequence for any n values, so
// that it can sort the values of several pixels at once, one pixel in each lane of SIMD
// registers (the reduced frames' median in hrti/frame_registration.cpp, the stack's median and
// quantiles in hrti/stack_median.cpp). Only min and max move values, so the sorted
// values are exactly those std::sort or std::nth_element give.
#pragma once

#include <algorithm>
#include <utility>
#include <vector>

namespace surrogate::hrti {

using CompareExchanges = std::vector<std::pair<int, int>>;

// The compare-exchanges (i, j), i < j, each putting the smaller value at i, that sort n values.
inline CompareExchanges mergeExchangeSort(int n) {
  CompareExchanges pairs;
  if (n < 2) return pairs;
  int t = 0;
  while ((1 << t) < n) ++t;
  for (int p = 1 << (t - 1); p > 0; p >>= 1) {
    int q = 1 << (t - 1), r = 0, d = p;
    for (;;) {
      for (int i = 0; i + d < n; ++i)
        if ((i & p) == r) pairs.emplace_back(i, i + d);
      if (q == p) break;
      d = q - p;
      q >>= 1;
      r = p;
    }
  }
  return pairs;
}

// Of the compare-exchanges `pairs` that sort n values, those that the value left at position
// `rank` depends on, in their order: walking back from the last, one that touches a position
// still needed is kept and makes both its positions needed. The others only move values that
// nothing kept reads again, so position `rank` ends with the same value (a median of 36 values
// keeps 199 of the 241).
inline CompareExchanges neededFor(const CompareExchanges& pairs, int n, int rank) {
  std::vector<bool> needed(static_cast<std::size_t>(n), false);
  needed[static_cast<std::size_t>(rank)] = true;
  CompareExchanges kept;
  for (auto p = pairs.rbegin(); p != pairs.rend(); ++p) {
    const auto i = static_cast<std::size_t>(p->first), j = static_cast<std::size_t>(p->second);
    if (!needed[i] && !needed[j]) continue;
    kept.push_back(*p);
    needed[i] = needed[j] = true;
  }
  std::reverse(kept.begin(), kept.end());
  return kept;
}

}  // namespace surrogate::hrti
