#include "core/parallel.h"

#include <algorithm>
#include <atomic>
#include <exception>
#include <thread>
#include <vector>

namespace surrogate {

int effectiveThreads(int requested) {
  if (requested > 0) return requested;
  const unsigned hw = std::thread::hardware_concurrency();
  return hw == 0 ? 1 : static_cast<int>(hw);
}

void parallelForWorkers(std::size_t n, std::size_t chunk, int threads,
                        const std::function<void(int, std::size_t, std::size_t)>& fn) {
  if (n == 0) return;
  if (chunk == 0) chunk = 1;
  const std::size_t chunks = (n + chunk - 1) / chunk;
  const std::size_t workers = std::min<std::size_t>(chunks, std::max(1, threads));
  std::vector<std::exception_ptr> errors(chunks);
  std::atomic<std::size_t> next{0};
  auto work = [&](int worker) {
    for (std::size_t c = next++; c < chunks; c = next++) {
      try {
        fn(worker, c * chunk, std::min(n, (c + 1) * chunk));
      } catch (...) {
        errors[c] = std::current_exception();
      }
    }
  };
  if (workers <= 1) {
    work(0);
  } else {
    std::vector<std::thread> pool;
    pool.reserve(workers - 1);
    for (std::size_t i = 1; i < workers; ++i) pool.emplace_back(work, static_cast<int>(i));
    work(0);
    for (auto& t : pool) t.join();
  }
  for (auto& e : errors)
    if (e) std::rethrow_exception(e);
}

void parallelFor(std::size_t n, std::size_t chunk, int threads,
                 const std::function<void(std::size_t, std::size_t)>& fn) {
  parallelForWorkers(n, chunk, threads, [&](int, std::size_t b, std::size_t e) { fn(b, e); });
}

}  // namespace surrogate
