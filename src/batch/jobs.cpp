#include "batch/jobs.h"

#include <fcntl.h>
#include <signal.h>
#include <sys/prctl.h>
#include <sys/resource.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>

#include "core/error.h"

namespace surrogate::batch {

namespace {

// An unnamed file in $TMPDIR (or /tmp), for a child's output.
int unnamedFile() {
  const char* dir = std::getenv("TMPDIR");
  std::string folder = dir && *dir ? dir : "/tmp";
  int fd = ::open(folder.c_str(), O_TMPFILE | O_RDWR | O_CLOEXEC, 0600);
  if (fd < 0) {  // a file system without O_TMPFILE: a named file, unlinked at once
    std::string name = folder + "/surrogate-batch-XXXXXX";
    fd = ::mkostemp(name.data(), O_CLOEXEC);
    if (fd >= 0) ::unlink(name.c_str());
  }
  if (fd < 0)
    throw Error(ErrorKind::Internal, folder, "batch",
                std::string("cannot make a temporary file for a job's output (") + std::strerror(errno) +
                    "); set TMPDIR to a folder that can be written");
  return fd;
}

std::string readAll(int fd) {
  std::string text;
  if (::lseek(fd, 0, SEEK_SET) < 0) return text;
  char buffer[1 << 15];
  for (;;) {
    const ssize_t n = ::read(fd, buffer, sizeof buffer);
    if (n < 0 && errno == EINTR) continue;
    if (n <= 0) break;
    text.append(buffer, static_cast<std::size_t>(n));
  }
  return text;
}

// The child's peak resident memory so far, bytes (VmHWM); 0 when it cannot be read.
std::uint64_t peakSoFar(pid_t pid) {
  std::ifstream status("/proc/" + std::to_string(pid) + "/status");
  std::string line;
  while (std::getline(status, line))
    if (line.rfind("VmHWM:", 0) == 0) return std::strtoull(line.c_str() + 6, nullptr, 10) * 1024;
  return 0;
}

}  // namespace

std::string selfExecutable() {
  std::error_code ec;
  const auto p = std::filesystem::read_symlink("/proc/self/exe", ec);
  if (ec)
    throw Error(ErrorKind::Internal, "/proc/self/exe", "batch",
                "cannot find the surrogate program to run the jobs (" + ec.message() + "); /proc must be mounted");
  return p.string();
}

Child::Child(const std::string& program, const std::vector<std::string>& arguments, std::uint64_t memoryBudget)
    : budget_(memoryBudget) {
  outFd_ = unnamedFile();
  errFd_ = unnamedFile();
  std::vector<std::string> args;
  args.push_back(program);
  args.insert(args.end(), arguments.begin(), arguments.end());
  std::vector<char*> argv;
  for (std::string& a : args) argv.push_back(a.data());
  argv.push_back(nullptr);
  const pid_t parent = ::getpid();
  started_ = std::chrono::steady_clock::now();
  pid_ = ::fork();
  if (pid_ < 0)
    throw Error(ErrorKind::Internal, program, "batch",
                std::string("cannot start a job (") + std::strerror(errno) + "); lower --jobs");
  if (pid_ == 0) {
    // Only async-signal-safe calls from here to exec.
    ::prctl(PR_SET_PDEATHSIG, SIGKILL);
    if (::getppid() != parent) ::_exit(127);  // the batch ended before the line above
    ::dup2(outFd_, 1);
    ::dup2(errFd_, 2);
    const int devNull = ::open("/dev/null", O_RDONLY);
    if (devNull >= 0) ::dup2(devNull, 0);
    ::execv(argv[0], argv.data());
    ::_exit(127);
  }
}

Child::~Child() {
  if (pid_ > 0 && !done_) {
    ::kill(pid_, SIGKILL);
    int status = 0;
    ::waitpid(pid_, &status, 0);
  }
  if (outFd_ >= 0) ::close(outFd_);
  if (errFd_ >= 0) ::close(errFd_);
}

bool Child::poll() {
  if (done_) return true;
  int status = 0;
  struct rusage usage {};
  const pid_t r = ::wait4(pid_, &status, WNOHANG, &usage);
  if (r == 0) {
    if (budget_ > 0 && !result_.overBudget) {
      const std::uint64_t peak = peakSoFar(pid_);
      if (peak > budget_) {
        result_.overBudget = true;
        observedPeak_ = peak;
        ::kill(pid_, SIGKILL);
      }
    }
    return false;
  }
  done_ = true;
  result_.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - started_).count();
  if (r < 0) {
    result_.exit = 128;
    result_.err = std::string("the job was lost (") + std::strerror(errno) + ")";
    return true;
  }
  // The kernel's two counts of the peak differ by a few pages (VmHWM passed 64 MiB where
  // ru_maxrss said 63.7): the larger, so that a job stopped for its memory never shows a peak
  // within its budget.
  result_.peakMemory = std::max(static_cast<std::uint64_t>(usage.ru_maxrss) * 1024, observedPeak_);
  result_.exit = WIFEXITED(status) ? WEXITSTATUS(status) : WIFSIGNALED(status) ? 128 + WTERMSIG(status) : 128;
  result_.out = readAll(outFd_);
  result_.err = readAll(errFd_);
  return true;
}

}  // namespace surrogate::batch
