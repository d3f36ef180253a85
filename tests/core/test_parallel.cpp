#include <catch2/catch.hpp>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <numeric>
#include <stdexcept>
#include <thread>
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

TEST_CASE("parallelForWorkers names each worker once: its chunks never run at the same time") {
  for (int threads : {1, 2, 4}) {
    std::vector<int> hits(500, 0);
    // One flag per worker, raised while one of its chunks runs: a chunk finding its worker's
    // flag already up would share per-worker scratch with another running chunk.
    std::vector<std::atomic<int>> busy(static_cast<std::size_t>(threads));
    std::atomic<int> clashes{0}, outside{0};
    std::vector<std::atomic<int>> chunksOf(static_cast<std::size_t>(threads));
    parallelForWorkers(hits.size(), 3, threads, [&](int worker, std::size_t b, std::size_t e) {
      if (worker < 0 || worker >= threads) {
        ++outside;
        return;
      }
      if (busy[worker].exchange(1) != 0) ++clashes;
      ++chunksOf[worker];
      for (std::size_t i = b; i < e; ++i) hits[i]++;
      std::this_thread::sleep_for(std::chrono::microseconds(50));  // chunks overlap in time
      busy[worker] = 0;
    });
    CHECK(outside == 0);
    CHECK(clashes == 0);
    CHECK(std::accumulate(hits.begin(), hits.end(), 0) == 500);
    CHECK(*std::min_element(hits.begin(), hits.end()) == 1);
    int total = 0;
    for (auto& c : chunksOf) total += c;
    CHECK(total == 167);  // ceil(500 / 3)
  }
}
