#include <catch2/catch.hpp>

#include <numeric>
#include <stdexcept>
#include <vector>

#include "core/parallel.h"

using namespace surrogate;

TEST_CASE("parallelFor visits every index exactly once at any thread count") {
  for (int threads : {1, 2, 3, 8}) {
    std::vector<int> hits(1000, 0);
    parallelFor(hits.size(), 7, threads, [&](std::size_t b, std::size_t e) {
      for (std::size_t i = b; i < e; ++i) hits[i]++;
    });
    REQUIRE(std::accumulate(hits.begin(), hits.end(), 0) == 1000);
    REQUIRE(*std::min_element(hits.begin(), hits.end()) == 1);
  }
}

TEST_CASE("parallelFor rethrows an exception from a worker") {
  REQUIRE_THROWS_AS(parallelFor(100, 10, 2, [](std::size_t b, std::size_t) {
                      if (b == 50) throw std::runtime_error("chunk 5");
                    }),
                    std::runtime_error);
}
