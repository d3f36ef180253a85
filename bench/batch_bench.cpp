// Throughput of a backlog (issue 44, item 5): N generated captures (default 40 of 24 images at
// 1200x800, as `surrogate-generate --images 24 --width 1200 --height 800` makes them) taken
// through run, pack and verify, each way on a fresh copy of the captures:
//   loop       a plain shell loop of `surrogate run`, `pack -o NAME.zip` and `verify`, one
//              capture after the other, each command on every core (the cost without a batch)
//   batch-J    `surrogate batch LIST -o LEDGER --jobs J` for each J of --jobs (each job gets
//              the cores divided among the jobs)
//   parallel   the script `surrogate batch --jobs 2 --emit parallel` writes, run by sh (GNU
//              parallel), when `parallel` is on the PATH
// For each: the wall time, captures per hour, the speed-up over batch-1, the peak resident
// memory of the largest job (the ledger's peakMemory), and the batch's own overhead: its wall
// time less the loop's (1 job), from hashing the carriers and packages, the ledger's appends
// and starting the jobs.
//
//   batch_bench --surrogate PATH --generator PATH [--captures 40] [--images 24] [--width 1200]
//               [--height 800] [--jobs 1,2] [--threads N] [--dir DIR] [--keep] [--no-report]
//
// --threads 1 puts every command and job on one thread: the speed-up of J jobs is then what
// the jobs add, not what a job's own threads already took of the cores.
//
// Figures only: it passes or fails on none of them (ctest label "bench").
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

namespace fs = std::filesystem;

namespace {

std::string quote(const std::string& s) {
  std::string out = "'";
  for (char c : s) out += c == '\'' ? std::string("'\\''") : std::string(1, c);
  return out + "'";
}

double shell(const std::string& command) {
  const auto t0 = std::chrono::steady_clock::now();
  const int status = std::system(command.c_str());
  const double s = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  if (status != 0) {
    std::fprintf(stderr, "batch_bench: failed (%d): %s\n", status, command.c_str());
    std::exit(1);
  }
  return s;
}

std::vector<int> parseList(const std::string& text) {
  std::vector<int> out;
  std::stringstream in(text);
  for (std::string part; std::getline(in, part, ',');) out.push_back(std::atoi(part.c_str()));
  return out;
}

// The largest "peakMemory" of a ledger's lines, bytes (a plain scan: the key is a number).
unsigned long long largestPeak(const fs::path& ledger) {
  std::ifstream in(ledger);
  unsigned long long most = 0;
  for (std::string line; std::getline(in, line);) {
    const std::size_t at = line.find("\"peakMemory\":");
    if (at != std::string::npos) most = std::max(most, std::strtoull(line.c_str() + at + 13, nullptr, 10));
  }
  return most;
}

std::size_t lines(const fs::path& file) {
  std::ifstream in(file);
  std::size_t n = 0;
  for (std::string line; std::getline(in, line);) ++n;
  return n;
}

}  // namespace

int main(int argc, char** argv) {
  std::string surrogate, generator, dirArg;
  int captures = 40, images = 24, width = 1200, height = 800;
  std::vector<int> jobs = {1, 2};
  bool keep = false, noReport = false;
  int threads = 0;  // 0: each way's default
  for (int i = 1; i < argc; ++i) {
    const std::string a = argv[i];
    const auto next = [&] { return i + 1 < argc ? std::string(argv[++i]) : std::string(); };
    if (a == "--surrogate") surrogate = next();
    else if (a == "--generator") generator = next();
    else if (a == "--captures") captures = std::atoi(next().c_str());
    else if (a == "--images") images = std::atoi(next().c_str());
    else if (a == "--width") width = std::atoi(next().c_str());
    else if (a == "--height") height = std::atoi(next().c_str());
    else if (a == "--jobs") jobs = parseList(next());
    else if (a == "--dir") dirArg = next();
    else if (a == "--keep") keep = true;
    else if (a == "--no-report") noReport = true;
    else if (a == "--threads") threads = std::atoi(next().c_str());
    else {
      std::fprintf(stderr, "usage: batch_bench --surrogate PATH --generator PATH [--captures N] [--images N] "
                           "[--width W] [--height H] [--jobs 1,2] [--threads N] [--dir DIR] [--keep] [--no-report]\n");
      return 2;
    }
  }
  if (surrogate.empty() || generator.empty()) {
    std::fprintf(stderr, "batch_bench: give --surrogate and --generator\n");
    return 2;
  }
  const fs::path dir = dirArg.empty() ? fs::temp_directory_path() / ("batch-bench-" + std::to_string(::getpid())) : fs::path(dirArg);
  fs::create_directories(dir / "source");
  std::printf("batch_bench: %d captures of %d images at %dx%d%s, on %ld cores\n", captures, images, width, height,
              noReport ? " (no reports)" : "", sysconf(_SC_NPROCESSORS_ONLN));
  for (int i = 1; i <= captures; ++i)
    shell(quote(generator) + " --out " + quote((dir / "source" / ("cap" + std::to_string(i))).string()) +
          " --images " + std::to_string(images) + " --width " + std::to_string(width) + " --height " +
          std::to_string(height) + " --seed " + std::to_string(i) + " > /dev/null && rm -rf " +
          quote((dir / "source" / ("cap" + std::to_string(i)) / "truth").string()));
  // --threads N: every command and job on N threads, so that jobs compare at equal threads.
  const std::string report = std::string(noReport ? " --no-report" : "") +
                             (threads > 0 ? " --threads " + std::to_string(threads) : "");
  const std::string verifyThreads = threads > 0 ? " --threads " + std::to_string(threads) : "";

  // A fresh copy of the captures and their list for one way of running.
  const auto fresh = [&](const std::string& name) {
    const fs::path work = dir / name;
    fs::remove_all(work);
    fs::create_directories(work);
    std::ofstream list(work / "list.txt");
    for (int i = 1; i <= captures; ++i) {
      const std::string cap = "cap" + std::to_string(i);
      fs::copy(dir / "source" / cap, work / cap, fs::copy_options::recursive);
      list << (work / cap).string() << "\n";
    }
    return work;
  };

  std::printf("%-10s %9s %14s %9s %14s %12s\n", "way", "wall s", "captures/hour", "speed-up", "largest job", "ledger lines");
  double loopSeconds = 0, oneJob = 0;
  {
    const fs::path work = fresh("loop");
    std::string script;
    for (int i = 1; i <= captures; ++i) {
      const std::string cap = quote((work / ("cap" + std::to_string(i))).string());
      const std::string zip = quote((work / ("cap" + std::to_string(i))).string() + ".zip");
      script += quote(surrogate) + " run " + cap + " --quiet" + report + " > /dev/null && " + quote(surrogate) +
                " pack " + cap + " -o " + zip + " --quiet" + report + " > /dev/null && " + quote(surrogate) +
                " verify " + zip + verifyThreads + " --quiet > /dev/null && ";
    }
    loopSeconds = shell(script + "true");
    std::printf("%-10s %9.1f %14.1f %9s %14s %12s\n", "loop", loopSeconds, captures / loopSeconds * 3600, "-", "-", "-");
  }
  for (int j : jobs) {
    const fs::path work = fresh("batch-" + std::to_string(j));
    const double s = shell(quote(surrogate) + " batch " + quote((work / "list.txt").string()) + " -o " +
                           quote((work / "ledger.jsonl").string()) + " --jobs " + std::to_string(j) + report + " --quiet");
    if (j == 1) oneJob = s;
    char speed[32] = "-";
    if (oneJob > 0) std::snprintf(speed, sizeof speed, "%.2fx", oneJob / s);
    std::printf("%-10s %9.1f %14.1f %9s %11.0f MB %12zu\n", ("batch-" + std::to_string(j)).c_str(), s,
                captures / s * 3600, speed, largestPeak(work / "ledger.jsonl") / 1e6, lines(work / "ledger.jsonl"));
  }
  if (std::system("parallel --version > /dev/null 2>&1") == 0) {
    const fs::path work = fresh("parallel");
    const std::string ledger = quote((work / "ledger.jsonl").string());
    shell(quote(surrogate) + " batch " + quote((work / "list.txt").string()) + " -o " + ledger + " --jobs 2" + report +
          " --emit parallel > " + quote((work / "run.sh").string()));
    const double s = shell("cd " + quote(work.string()) + " && HOME=" + quote(work.string()) + " sh run.sh");
    char speed[32] = "-";
    if (oneJob > 0) std::snprintf(speed, sizeof speed, "%.2fx", oneJob / s);
    std::printf("%-10s %9.1f %14.1f %9s %11.0f MB %12zu\n", "parallel-2", s, captures / s * 3600, speed,
                largestPeak(work / "ledger.jsonl") / 1e6, lines(work / "ledger.jsonl"));
  } else {
    std::printf("parallel-2: GNU parallel is not on the PATH (Debian's parallel): not measured\n");
  }
  if (oneJob > 0)
    std::printf("batch overhead at 1 job: %.1f s over the plain loop's %.1f s (%.2f s a capture)\n", oneJob - loopSeconds,
                loopSeconds, (oneJob - loopSeconds) / captures);
  if (!keep) fs::remove_all(dir);
  else std::printf("kept: %s\n", dir.c_str());
  return 0;
}
