// Batcher's merge-exchange sort (Knuth, The Art of Computer Programming, 5.2.2, Algorithm M) as
// its list of compare-exchanges: a sorting network, the same fixed sequence for any n values, so
// that it can sort the values of several pixels at once, one pixel in each lane of SIMD
// registers (the reduced frames' median in hrti/frame_registration.cpp, the stack's median and
// quantiles in hrti/stack_median.cpp). Only min and max move values, so the sorted
// values are exactly those std::sort or std::nth_element give.
#pragma once

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

}  // namespace surrogate::hrti
