// DeferredTasks (src/core/deferred_tasks.h): tasks run beside a caller's one-thread work and
// the rest at finish, each once, errors rethrown in task order.
#include <catch2/catch.hpp>

#include <atomic>
#include <chrono>
#include <stdexcept>
#include <thread>
#include <vector>

#include "core/deferred_tasks.h"

using surrogate::DeferredTasks;

namespace {

std::vector<std::function<void()>> counting(std::vector<std::atomic<int>>& runs, std::atomic<int>& onCaller,
                                            std::thread::id caller) {
  std::vector<std::function<void()>> tasks;
  for (std::size_t k = 0; k < runs.size(); ++k)
    tasks.push_back([&runs, &onCaller, caller, k] {
      ++runs[k];
      if (std::this_thread::get_id() == caller) ++onCaller;
      std::this_thread::sleep_for(std::chrono::milliseconds(2));
    });
  return tasks;
}

}  // namespace

TEST_CASE("deferred tasks run beside the caller's work on another thread, the rest at finish, each once") {
  std::vector<std::atomic<int>> runs(100);
  std::atomic<int> onCaller{0};
  DeferredTasks tasks(counting(runs, onCaller, std::this_thread::get_id()));
  int besideRuns = 0;
  tasks.besides([&] {
    // The caller's work ends once the other thread has run a task (at most 10 s on a loaded
    // machine), long before it could run all 100 (2 ms each).
    const auto start = std::chrono::steady_clock::now();
    while (runs[0] == 0 && std::chrono::steady_clock::now() - start < std::chrono::seconds(10))
      std::this_thread::sleep_for(std::chrono::microseconds(200));
    for (const auto& r : runs) besideRuns += r.load();
  });
  CHECK(onCaller == 0);  // beside: none on the caller's thread
  CHECK(besideRuns > 0);
  CHECK(besideRuns < 100);
  tasks.finish(2);
  for (const auto& r : runs) CHECK(r == 1);
}

TEST_CASE("deferred tasks' errors come out of finish in task order, and the caller's work's out of besides") {
  std::vector<std::function<void()>> list;
  for (int k = 0; k < 6; ++k)
    list.push_back([k] {
      if (k == 2 || k == 4) throw std::runtime_error("task " + std::to_string(k));
    });
  DeferredTasks tasks(std::move(list));
  CHECK_THROWS_WITH(tasks.besides([] { throw std::runtime_error("the caller's"); }), "the caller's");
  CHECK_THROWS_WITH(tasks.finish(3), "task 2");
}

TEST_CASE("deferred tasks with one thread run at finish, in order, on the caller") {
  std::vector<int> order;
  std::vector<std::function<void()>> list;
  for (int k = 0; k < 5; ++k) list.push_back([&order, k] { order.push_back(k); });
  DeferredTasks tasks(std::move(list));
  tasks.finish(1);
  CHECK(order == std::vector<int>{0, 1, 2, 3, 4});
}
