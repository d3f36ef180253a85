#include "core/deferred_tasks.h"

#include <algorithm>
#include <system_error>
#include <thread>

#include "core/parallel.h"

namespace surrogate {

DeferredTasks::DeferredTasks(std::vector<std::function<void()>> tasks)
    : tasks_(std::move(tasks)), errors_(tasks_.size()) {}

void DeferredTasks::run(const std::atomic<bool>& stop) {
  for (std::size_t k; !stop.load(std::memory_order_relaxed) && (k = next_.fetch_add(1)) < tasks_.size();) {
    try {
      tasks_[k]();
    } catch (...) {
      errors_[k] = std::current_exception();
    }
  }
}

void DeferredTasks::besides(const std::function<void()>& work) {
  std::atomic<bool> stop{false};
  std::thread helper;
  if (next_.load() < tasks_.size()) {
    try {
      helper = std::thread([this, &stop] { run(stop); });
    } catch (const std::system_error&) {
      // No thread: the tasks wait for finish().
    }
  }
  std::exception_ptr failed;
  try {
    work();
  } catch (...) {
    failed = std::current_exception();
  }
  stop.store(true, std::memory_order_relaxed);
  if (helper.joinable()) helper.join();
  if (failed) std::rethrow_exception(failed);
}

void DeferredTasks::finish(int threads) {
  const std::atomic<bool> never{false};
  const int workers = std::max(1, effectiveThreads(threads));
  parallelFor(static_cast<std::size_t>(workers), 1, workers, [&](std::size_t, std::size_t) { run(never); });
  for (const std::exception_ptr& e : errors_)
    if (e) std::rethrow_exception(e);
}

}  // namespace surrogate
