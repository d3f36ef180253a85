#include <catch2/catch.hpp>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <numeric>
#include <stdexcept>
#include <string>
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

TEST_CASE("parallelFor rethrows the first failing chunk's exception, after every chunk ran") {
  std::atomic<int> ran{0};
  try {
    parallelFor(40, 1, 3, [&](std::size_t b, std::size_t) {
      ++ran;
      if (b == 7 || b == 30) throw std::runtime_error("chunk " + std::to_string(b));
    });
    FAIL("no exception");
  } catch (const std::runtime_error& e) {
    CHECK(std::string(e.what()) == "chunk 7");
  }
  CHECK(ran == 40);
}

TEST_CASE("parallelFor inside another's chunk, and on two threads at once, finishes") {
  // The kept threads are busy with the outer loop: the inner loops must get threads of their own.
  std::vector<std::atomic<int>> hits(64 * 50);
  parallelFor(64, 1, 4, [&](std::size_t b, std::size_t e) {
    for (std::size_t i = b; i < e; ++i)
      parallelFor(50, 4, 3, [&](std::size_t ib, std::size_t ie) {
        for (std::size_t j = ib; j < ie; ++j) ++hits[i * 50 + j];
      });
  });
  for (auto& h : hits) REQUIRE(h == 1);
  std::vector<std::atomic<int>> other(2 * 2000);
  std::vector<std::thread> callers;
  for (int t = 0; t < 2; ++t)
    callers.emplace_back([&, t] {
      for (int round = 0; round < 50; ++round)
        parallelForWorkers(2000, 16, 2, [&](int worker, std::size_t b, std::size_t e) {
          if (worker < 0 || worker > 1) return;
          for (std::size_t i = b; i < e; ++i) other[t * 2000 + i] += 1;
        });
    });
  for (auto& c : callers) c.join();
  for (auto& h : other) REQUIRE(h == 50);
}

TEST_CASE("parallelFor with one thread runs on the calling thread") {
  const auto caller = std::this_thread::get_id();
  std::atomic<int> elsewhere{0};
  parallelFor(100, 1, 1, [&](std::size_t, std::size_t) {
    if (std::this_thread::get_id() != caller) ++elsewhere;
  });
  CHECK(elsewhere == 0);
}
