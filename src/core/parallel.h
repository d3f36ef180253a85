// Deterministic parallel loops.
//
// parallelFor(n, threads, fn) calls fn(begin, end) on contiguous, statically assigned chunks
// of [0, n). The split depends only on n and the chunk size, never on timing, so any work
// whose chunks write disjoint outputs gives bit-identical results at any thread count.
// Reductions must be done by the caller per chunk and combined in chunk order.
#pragma once

#include <cstddef>
#include <functional>

namespace surrogate {

// Number of worker threads to use: `requested` if > 0, else the hardware concurrency.
int effectiveThreads(int requested);

// Runs fn(begin, end) for consecutive chunks of `chunk` items (the last may be shorter).
// Chunks are handed out in order to `threads` workers; exceptions are rethrown (the first by
// chunk order) after all workers finish.
void parallelFor(std::size_t n, std::size_t chunk, int threads,
                 const std::function<void(std::size_t, std::size_t)>& fn);

// As parallelFor, with fn(worker, begin, end) also told which worker runs the chunk: 0 to
// max(1, threads) - 1, each worker one thread, so scratch memory allocated once per worker
// before the loop can be handed to every chunk that worker runs.
void parallelForWorkers(std::size_t n, std::size_t chunk, int threads,
                        const std::function<void(int, std::size_t, std::size_t)>& fn);

}  // namespace surrogate
