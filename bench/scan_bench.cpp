// Capture scanning against the number of files (issue 39, item 7): a small generated capture
// (8 shots of 400x300, DNG and JPEG, as `surrogate-generate --images 8 --width 400 --height 300
// --sphere-radius 45 --seed 7` makes it) with N other files beside it (notes/batch-NNN/, 1000 a
// folder, a few bytes each), which `surrogate run` records with role "other" and packs.
//
// For each N it times, on a fresh copy of the capture:
//   scan    capture::scanCapture in this process (names listed and judged, headers read)
//   run     `surrogate run CAPTURE --no-report --quiet` (every file hashed and recorded, the
//           carrier saved after each step), wall and CPU time (user + system), peak memory
//   rerun   the same again: the run compares every file with the carrier of the first
// and the time per file, which stays about constant when the cost is linear in the files.
//
//   scan_bench --surrogate PATH [--files 10000,100000] [--dir DIR] [--keep]
//
// Figures only: it passes or fails on none of them (ctest label "bench").
#include <fcntl.h>
#include <sys/resource.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include "capture/capture.h"
#include "generator/capture_generator.h"

namespace fs = std::filesystem;
using namespace surrogate;

namespace {

struct Timing {
  double wall = 0, cpu = 0, peakMiB = 0;
  int status = 0;
};

double cpuSeconds(const rusage& u) {
  return double(u.ru_utime.tv_sec + u.ru_stime.tv_sec) + 1e-6 * double(u.ru_utime.tv_usec + u.ru_stime.tv_usec);
}

Timing runChild(const std::vector<std::string>& args) {
  std::vector<char*> argv;
  for (const std::string& a : args) argv.push_back(const_cast<char*>(a.c_str()));
  argv.push_back(nullptr);
  const auto t0 = std::chrono::steady_clock::now();
  const pid_t pid = fork();
  if (pid == 0) {
    const int null = open("/dev/null", O_WRONLY);  // the run's summary: not the figures
    if (null >= 0) dup2(null, STDOUT_FILENO);
    execv(argv[0], argv.data());
    _exit(127);
  }
  int status = 0;
  rusage usage{};
  wait4(pid, &status, 0, &usage);
  Timing t;
  t.wall = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  t.cpu = cpuSeconds(usage);
  t.peakMiB = usage.ru_maxrss / 1024.0;
  t.status = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  return t;
}

// The other files: notes/batch-NNN/note-NNNNNN.txt, 1000 a folder.
void addOtherFiles(const fs::path& capture, int files) {
  for (int i = 0; i < files; ++i) {
    char rel[64];
    std::snprintf(rel, sizeof rel, "notes/batch-%03d/note-%06d.txt", i / 1000, i);
    const fs::path path = capture / rel;
    if (i % 1000 == 0) fs::create_directories(path.parent_path());
    std::ofstream(path) << "note " << i << "\n";
  }
}

std::vector<int> parseCounts(const std::string& text) {
  std::vector<int> out;
  std::stringstream in(text);
  for (std::string item; std::getline(in, item, ',');) out.push_back(std::atoi(item.c_str()));
  return out;
}

}  // namespace

int main(int argc, char** argv) {
  std::string surrogate;
  std::vector<int> counts = {10000, 100000};
  fs::path dir = fs::temp_directory_path() / "surrogate-scan-bench";
  bool keep = false;
  for (int i = 1; i < argc; ++i) {
    const std::string a = argv[i];
    if (a == "--keep") { keep = true; continue; }
    if (i + 1 >= argc) break;
    if (a == "--surrogate") surrogate = argv[++i];
    else if (a == "--files") counts = parseCounts(argv[++i]);
    else if (a == "--dir") dir = argv[++i];
  }
  if (surrogate.empty()) {
    std::fprintf(stderr, "usage: scan_bench --surrogate PATH [--files 10000,100000] [--dir DIR] [--keep]\n");
    return 2;
  }
  fs::remove_all(dir);
  generator::GeneratorOptions o;
  o.images = 8;
  o.width = 400;
  o.height = 300;
  o.sphereRadius = 45;
  o.seed = 7;
  const fs::path base = dir / "base";
  generator::writeCapture(o, base);

  std::printf("%8s  %22s  %34s  %34s\n", "files", "scan (in process)", "surrogate run --no-report",
              "run again");
  std::printf("%8s  %9s %12s  %9s %9s %14s  %9s %9s %14s\n", "", "wall s", "us/file", "wall s",
              "CPU s", "CPU us/file", "wall s", "CPU s", "CPU us/file");
  for (int n : counts) {
    const fs::path capture = dir / ("capture-" + std::to_string(n));
    fs::remove_all(capture);
    fs::copy(base, capture, fs::copy_options::recursive);
    addOtherFiles(capture, n);

    const auto t0 = std::chrono::steady_clock::now();
    const capture::CaptureLayout layout = capture::scanCapture(capture, 0);
    const double scan = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    if (layout.others.size() < static_cast<std::size_t>(n))
      std::fprintf(stderr, "the scan found %zu other files, not %d\n", layout.others.size(), n);

    const std::vector<std::string> command = {surrogate, "run", capture.string(), "--no-report", "--quiet"};
    const Timing run = runChild(command);
    const Timing rerun = runChild(command);
    const double perFile = 1e6 / double(n);
    std::printf("%8d  %9.2f %12.1f  %9.2f %9.2f %14.1f  %9.2f %9.2f %14.1f   peak %.0f MiB%s\n", n, scan,
                scan * perFile, run.wall, run.cpu, run.cpu * perFile, rerun.wall, rerun.cpu,
                rerun.cpu * perFile, std::max(run.peakMiB, rerun.peakMiB),
                run.status == 0 && rerun.status == 0 ? "" : "  FAILED");
    std::fflush(stdout);
    if (!keep) fs::remove_all(capture);
  }
  if (!keep) fs::remove_all(dir);
  return 0;
}
