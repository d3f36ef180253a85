// Independent tasks whose results are needed later, run where a core would otherwise be idle.
//
// A step can leave work that nothing reads until the carrier is saved (the decoded images'
// pixel digests) for a later step that keeps one thread busy and another idle (the colour
// chart search, a library call on one thread): besides(work) runs `work` on the calling thread
// and, meanwhile, as many of the tasks as fit on one other thread; finish() runs the rest on
// the threads given. Each task writes its own result, so which thread ran it, and when,
// changes nothing.
//
//   DeferredTasks digests(std::move(tasks));
//   digests.besides([&] { found = findChart(frame); });   // tasks on the other core meanwhile
//   digests.finish(threads);                                // the rest; errors rethrown
#pragma once

#include <atomic>
#include <cstddef>
#include <exception>
#include <functional>
#include <vector>

namespace surrogate {

class DeferredTasks {
 public:
  explicit DeferredTasks(std::vector<std::function<void()>> tasks);
  DeferredTasks(const DeferredTasks&) = delete;
  DeferredTasks& operator=(const DeferredTasks&) = delete;

  // Runs `work` on this thread and tasks on one other thread until `work` returns (the task
  // running then is let end); `work`'s exception is rethrown after that. Without a thread to be
  // had, just `work`.
  void besides(const std::function<void()>& work);
  // Runs the tasks not yet run on `threads` threads (parallelFor's count), then rethrows the
  // first task's error, in task order.
  void finish(int threads);

 private:
  // Runs tasks in order until none is left or `stop` is set.
  void run(const std::atomic<bool>& stop);

  std::vector<std::function<void()>> tasks_;
  std::vector<std::exception_ptr> errors_;
  std::atomic<std::size_t> next_{0};
};

}  // namespace surrogate
