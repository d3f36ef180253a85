// A job's step as a child process: the `surrogate` program itself (/proc/self/exe) running the
// ordinary command (run, pack, verify) on one capture or package, so that a crash or a memory
// overrun of one job ends that job and not the batch.
//
// The child's standard output and error go to unnamed temporary files (a command's --json
// report can be larger than a pipe holds), read when it ends. It is killed with the batch
// (PR_SET_PDEATHSIG): a batch killed with kill -9 leaves no job running on a capture that the
// next batch would find locked. Its peak resident memory is wait4's ru_maxrss; with a memory
// budget, the parent reads the child's VmHWM (its peak so far, /proc/PID/status) every
// kPollInterval and kills it once the peak passes the budget: a peak between two reads is still
// seen at the next, since VmHWM never decreases.
#pragma once

#include <chrono>
#include <cstdint>
#include <string>
#include <sys/types.h>
#include <vector>

namespace surrogate::batch {

inline constexpr std::chrono::milliseconds kPollInterval{50};

struct ChildResult {
  int exit = 0;                  // exit code, or 128 + the signal that ended it
  std::uint64_t peakMemory = 0;  // bytes
  bool overBudget = false;       // killed for passing the memory budget
  std::string out, err;          // what it printed
  double seconds = 0;
};

class Child {
 public:
  // Starts `program` with `arguments` (argv[1..]); `memoryBudget` 0: no watch. Throws
  // Error(Internal) when no process can be started.
  Child(const std::string& program, const std::vector<std::string>& arguments, std::uint64_t memoryBudget);
  ~Child();  // kills a child still running (the batch is ending on an error)
  Child(const Child&) = delete;
  Child& operator=(const Child&) = delete;

  // Whether it has ended (then `result()` holds what it did); checks the memory budget.
  bool poll();
  const ChildResult& result() const { return result_; }
  pid_t pid() const { return pid_; }

 private:
  pid_t pid_ = -1;
  int outFd_ = -1, errFd_ = -1;
  std::uint64_t budget_ = 0;
  std::uint64_t observedPeak_ = 0;  // VmHWM when it passed the budget
  bool done_ = false;
  std::chrono::steady_clock::time_point started_;
  ChildResult result_;
};

// The running program's own path (/proc/self/exe), for the children.
std::string selfExecutable();

}  // namespace surrogate::batch
