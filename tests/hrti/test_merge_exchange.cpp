// hrti::mergeExchangeSort: its compare-exchanges, applied one by one (as the AVX2 medians of
// hrti/stack_median.cpp and hrti/frame_registration.cpp apply them to eight or sixteen pixels at
// once), sort any n values exactly, ties and repeated values included, as std::sort does.
#include <algorithm>
#include <random>
#include <vector>

#include <catch2/catch.hpp>

#include "hrti/merge_exchange.h"

using surrogate::hrti::mergeExchangeSort;

TEST_CASE("the merge-exchange network sorts any count of values as std::sort does") {
  std::mt19937 rng(59);
  for (int n = 1; n <= 40; ++n) {
    const auto network = mergeExchangeSort(n);
    for (const auto& [i, j] : network) {
      CHECK(i < j);
      CHECK(j < n);
    }
    for (int trial = 0; trial < 200; ++trial) {
      // Few distinct values in some trials: ties must come out as std::sort puts them.
      const int distinct = trial % 2 ? 4 : 1 << 20;
      std::vector<float> values(static_cast<std::size_t>(n));
      for (float& v : values) v = static_cast<float>(rng() % distinct) / distinct;
      std::vector<float> expected = values;
      std::sort(expected.begin(), expected.end());
      for (const auto& [i, j] : network) {
        const float low = std::min(values[i], values[j]);
        values[j] = std::max(values[i], values[j]);
        values[i] = low;
      }
      CHECK(values == expected);
    }
  }
}
