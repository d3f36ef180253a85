// Where the time of `surrogate run` goes, step by step, against the decode floor (issue 59: a run
// at most 12x the floor; near lights at most 1.5x the far-light run).
//
// 1. Generates the captures once, kept in DIR between runs (made again only when their stamp
//    file differs): "small", 36 JPEG exports of 1200x800 at JPEG quality 92, sphere radius 80;
//    with --large also "large", 60 x 6000x4000 (radius min(w,h)/13, as pipeline_bench; takes
//    minutes); unless --no-near, "near": 36 x 1200x800 with two spheres and lights 3 frame
//    widths away.
// 2. Runs --rounds paired rounds per capture. A round is the decode floor (bench/decode_floor
//    --json --threads T on CAPTURE/jpeg-exports) and then `surrogate run CAPTURE --no-report
//    --quiet --threads T` from a clean start (assembly-files/ and finished-files/ removed), a
//    child process each: wall time and peak resident memory (wait4), and every step's seconds
//    as the carrier it wrote records them (read with the project's own carrier reader).
//    On "near" a round runs the floor, then `run --light-distance infinity` and `run
//    --light-distance 3`, in turns first (so that a drift of the machine's load is shared).
// 3. Prints per capture a table: each step (the RtiFit steps named with their basis), its median
//    seconds over the rounds, its share of the run's median wall time, and its seconds over the
//    median floor ("x floor"); "outside the steps" is the median over the rounds of the wall
//    time less the steps' sum (the process starting, the capture's scan outside a step, the
//    carrier written between steps), so the rows need not add up to the wall time exactly. Then
//    the run against the floor with the target, and each round's raw figures: on a noisy machine
//    read those before a median. For "near", far and near side by side with near/far per step.
// Figures only: the exit status is non-zero when a child fails or its carrier cannot be read,
// never on a time.
//
//   run_shares --surrogate PATH --floor PATH [--dir DIR] [--rounds N] [--threads N] [--large]
//              [--no-near]
#include <sys/resource.h>
#include <sys/wait.h>
#include <fcntl.h>
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cerrno>
#include <cstdio>
#include <cstdlib>
#include <exception>
#include <filesystem>
#include <fstream>
#include <map>
#include <string>
#include <thread>
#include <vector>

#include "carrier/carrier.h"
#include "generator/capture_generator.h"

namespace fs = std::filesystem;
using namespace surrogate;

namespace {

constexpr double kRunTarget = 12;        // issue 59: a run at most 12x the decode floor
constexpr double kNearTarget = 1.5;      // issue 59 item 3: near lights at most 1.5x the far run
constexpr int kDefaultRounds = 3;
constexpr int kJpegQuality = 92;
constexpr double kSmallSphereRadius = 80;
constexpr double kLargeRadiusDivisor = 13;  // as bench/pipeline_bench.cpp
constexpr double kNearDistance = 3;      // frame widths: near enough to matter, far enough that
                                         // the far run still accepts every highlight
constexpr double kMiB = 1024.0;          // ru_maxrss is in KiB

struct ChildRun {
  double seconds = 0;
  double peakMiB = 0;
  int status = -1;
  std::string output;  // standard output and error
};

// Runs a program as a child, its output collected (printed by the caller only when the child
// fails: a run's progress or diagnostics would break up the tables), and times it to its exit.
ChildRun runChild(const std::vector<std::string>& args) {
  std::vector<char*> argv;
  for (const std::string& a : args) argv.push_back(const_cast<char*>(a.c_str()));
  argv.push_back(nullptr);
  int pipeFds[2];
  if (pipe(pipeFds) != 0) return {};
  std::fflush(stdout);
  const auto t0 = std::chrono::steady_clock::now();
  const pid_t pid = fork();
  if (pid == 0) {
    close(pipeFds[0]);
    dup2(pipeFds[1], STDOUT_FILENO);
    dup2(pipeFds[1], STDERR_FILENO);
    close(pipeFds[1]);
    execv(argv[0], argv.data());
    _exit(127);
  }
  close(pipeFds[1]);
  ChildRun r;
  char buffer[4096];
  for (ssize_t n; (n = read(pipeFds[0], buffer, sizeof buffer)) != 0;) {
    if (n > 0) r.output.append(buffer, std::size_t(n));
    else if (errno != EINTR) break;
  }
  close(pipeFds[0]);
  int status = 0;
  rusage usage{};
  if (pid < 0 || wait4(pid, &status, 0, &usage) != pid) return r;
  r.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  r.peakMiB = usage.ru_maxrss / kMiB;
  r.status = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  return r;
}

double median(std::vector<double> v) {
  if (v.empty()) return 0;
  std::sort(v.begin(), v.end());
  const std::size_t h = v.size() / 2;
  return v.size() % 2 ? v[h] : (v[h - 1] + v[h]) / 2;
}

struct CaptureSpec {
  std::string name;  // its folder in DIR
  generator::GeneratorOptions options;
};

std::string describe(const generator::GeneratorOptions& o) {
  char text[160];
  std::snprintf(text, sizeof text, "%d x %dx%d JPEG q%d, %d sphere%s of radius %g", o.images, o.width, o.height,
                o.jpegQuality, o.spheres, o.spheres == 1 ? "" : "s", o.sphereRadius);
  std::string s = text;
  if (o.lightDistance > 0) {
    std::snprintf(text, sizeof text, ", lights %g frame widths away", o.lightDistance);
    s += text;
  }
  return s;
}

CaptureSpec jpegCapture(const std::string& name, int images, int width, int height, double radius) {
  CaptureSpec c{name, {}};
  c.options.images = images;
  c.options.width = width;
  c.options.height = height;
  c.options.sphereRadius = radius;
  c.options.jpegQuality = kJpegQuality;
  c.options.formats = generator::OutputFormats::Jpeg;
  return c;
}

// DIR/NAME/capture, generated when DIR/NAME/generated.txt does not hold the options' description.
fs::path prepare(const fs::path& dir, const CaptureSpec& spec) {
  const fs::path folder = dir / spec.name;
  const fs::path capture = folder / "capture";
  const fs::path stamp = folder / "generated.txt";
  const std::string want = describe(spec.options);
  std::string have;
  if (std::ifstream in{stamp}) std::getline(in, have);
  if (have != want) {
    fs::remove_all(folder);
    std::printf("generating %s: %s in %s ...\n", spec.name.c_str(), want.c_str(), capture.c_str());
    std::fflush(stdout);
    const auto t0 = std::chrono::steady_clock::now();
    generator::writeCapture(spec.options, capture);
    std::printf("  generated in %.1f s\n", std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count());
    std::ofstream(stamp) << want << "\n";
  }
  return capture;
}

struct Settings {
  std::string surrogate, floor;
  int threads = 0;
};

// The floor's wall time from decode_floor's JSON object; negative when it failed.
double runFloor(const Settings& s, const fs::path& capture) {
  const ChildRun r = runChild({s.floor, "--json", "--threads", std::to_string(s.threads),
                               (capture / "jpeg-exports").string()});
  const std::string key = "\"wall_s\":";
  const std::size_t at = r.output.find(key);
  if (r.status != 0 || at == std::string::npos) {
    std::fprintf(stderr, "run_shares: decode_floor failed (status %d) on %s:\n%s\n", r.status, capture.c_str(),
                 r.output.c_str());
    return -1;
  }
  return std::strtod(r.output.c_str() + at + key.size(), nullptr);
}

struct RunFigures {
  bool ok = false;
  double wall = 0, peakMiB = 0;
  std::vector<std::pair<std::string, double>> steps;  // in the carrier's order
};

// A step's name in the tables: its component, and its basis when its parameters name one (the
// two RtiFit steps).
std::string stepLabel(const carrier::Step& step) {
  const std::string basis = step.param("basis");
  return basis.empty() ? step.component : step.component + " " + basis;
}

RunFigures runSurrogate(const Settings& s, const fs::path& capture, const std::vector<std::string>& extra) {
  fs::remove_all(capture / "assembly-files");
  fs::remove_all(capture / "finished-files");
  std::vector<std::string> args = {s.surrogate, "run", capture.string(), "--no-report", "--quiet",
                                   "--threads", std::to_string(s.threads)};
  args.insert(args.end(), extra.begin(), extra.end());
  const ChildRun r = runChild(args);
  RunFigures f;
  f.wall = r.seconds;
  f.peakMiB = r.peakMiB;
  if (r.status != 0) {
    std::fprintf(stderr, "run_shares: surrogate run failed (status %d) on %s:\n%s\n", r.status, capture.c_str(),
                 r.output.c_str());
    return f;
  }
  try {
    const carrier::Carrier c = carrier::loadCarrier(capture / "assembly-files" / "carrier.xml");
    std::map<std::string, int> seen;
    for (const carrier::Step& step : c.process) {
      const carrier::Result* result = c.findResult(step.id);
      if (!result) continue;
      std::string label = stepLabel(step);
      if (seen[label]++ > 0) label += " (" + step.id + ")";  // the same component twice
      f.steps.emplace_back(label, result->seconds);
    }
    f.ok = true;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "run_shares: cannot read the carrier of %s: %s\n", capture.c_str(), e.what());
  }
  return f;
}

// One side of a table: the medians over the rounds.
struct Summary {
  std::vector<std::string> labels;        // in the order of the first round that has them
  std::map<std::string, double> seconds;  // median of the rounds that ran the step
  double wall = 0, outside = 0, floor = 0, peakMiB = 0;
};

Summary summarise(const std::vector<RunFigures>& runs, const std::vector<double>& floors) {
  Summary s;
  std::map<std::string, std::vector<double>> all;
  std::vector<double> walls, outside;
  for (const RunFigures& r : runs) {
    if (!r.ok) continue;
    double sum = 0;
    for (const auto& [label, seconds] : r.steps) {
      if (!all.count(label)) s.labels.push_back(label);
      all[label].push_back(seconds);
      sum += seconds;
    }
    walls.push_back(r.wall);
    outside.push_back(r.wall - sum);
    s.peakMiB = std::max(s.peakMiB, r.peakMiB);
  }
  for (const auto& [label, v] : all) s.seconds[label] = median(v);
  s.wall = median(walls);
  s.outside = median(outside);
  std::vector<double> good;
  for (double f : floors)
    if (f > 0) good.push_back(f);
  s.floor = median(good);
  return s;
}

double ratio(double a, double b) { return b > 0 ? a / b : 0; }

// "  0.412  30.1%   1.52": seconds, share of the wall time, times the floor.
std::string cells(double seconds, const Summary& s) {
  char text[64];
  std::snprintf(text, sizeof text, "%8.3f %6.1f%% %7.2f", seconds, 100 * ratio(seconds, s.wall), ratio(seconds, s.floor));
  return text;
}

constexpr const char* kBlankCells = "       -       -       -";

void printTarget(const char* prefix, const Summary& s) {
  std::printf("  %srun = %.1fx the decode floor (target at most %gx); peak %.0f MiB\n", prefix, ratio(s.wall, s.floor),
              kRunTarget, s.peakMiB);
}

void printTable(const Summary& s) {
  std::printf("  %-28s %8s %7s %7s\n", "step", "median s", "share", "x floor");
  for (const std::string& label : s.labels) std::printf("  %-28s %s\n", label.c_str(), cells(s.seconds.at(label), s).c_str());
  std::printf("  %-28s %s\n", "outside the steps", cells(s.outside, s).c_str());
  std::printf("  %-28s %s\n", "run (wall)", cells(s.wall, s).c_str());
  std::printf("  %-28s %8.3f\n", "decode floor", s.floor);
  printTarget("", s);
}

// Far and near side by side, with near/far per row.
void printPair(const Summary& far, const Summary& near) {
  std::printf("  %-28s %-24s   %-24s\n", "", "far: lights at infinity", "near: at the stated distance");
  std::printf("  %-28s %8s %7s %7s   %8s %7s %7s %9s\n", "step", "median s", "share", "x floor", "median s", "share",
              "x floor", "near/far");
  std::vector<std::string> labels = far.labels;
  for (const std::string& l : near.labels)
    if (std::find(labels.begin(), labels.end(), l) == labels.end()) labels.push_back(l);
  const auto row = [&](const std::string& label, const double* a, const double* b) {
    std::printf("  %-28s %s   %s", label.c_str(), a ? cells(*a, far).c_str() : kBlankCells,
                b ? cells(*b, near).c_str() : kBlankCells);
    if (a && b) std::printf(" %9.2f", ratio(*b, *a));
    std::printf("\n");
  };
  for (const std::string& label : labels) {
    const auto a = far.seconds.find(label), b = near.seconds.find(label);
    row(label, a == far.seconds.end() ? nullptr : &a->second, b == near.seconds.end() ? nullptr : &b->second);
  }
  row("outside the steps", &far.outside, &near.outside);
  row("run (wall)", &far.wall, &near.wall);
  std::printf("  %-28s %8.3f   %24s %8.3f\n", "decode floor", far.floor, "", near.floor);
  printTarget("far:  ", far);
  printTarget("near: ", near);
  std::printf("  near run / far run = %.2f (target at most %gx)\n", ratio(near.wall, far.wall), kNearTarget);
}

std::string roundCell(const char* name, const RunFigures& r) {
  char text[96];
  std::snprintf(text, sizeof text, "%s %.3f s (%.0f MiB)%s", name, r.wall, r.peakMiB, r.ok ? "" : " FAILED");
  return text;
}

// The capture's rounds and table; false when a child failed.
bool measureFar(const Settings& settings, const CaptureSpec& spec, const fs::path& capture, int rounds) {
  std::vector<double> floors;
  std::vector<RunFigures> runs;
  bool ok = true;
  std::printf("\n%s: %s; %d threads, %d rounds\n", spec.name.c_str(), describe(spec.options).c_str(), settings.threads,
              rounds);
  for (int i = 0; i < rounds; ++i) {
    floors.push_back(runFloor(settings, capture));
    runs.push_back(runSurrogate(settings, capture, {}));
    ok = ok && floors.back() > 0 && runs.back().ok;
    std::printf("  round %d: floor %.3f s, %s\n", i + 1, floors.back(), roundCell("run", runs.back()).c_str());
  }
  printTable(summarise(runs, floors));
  return ok;
}

bool measureNear(const Settings& settings, const CaptureSpec& spec, const fs::path& capture, int rounds) {
  std::vector<double> floors;
  std::vector<RunFigures> far, near;
  bool ok = true;
  char text[32];
  std::snprintf(text, sizeof text, "%g", spec.options.lightDistance);
  const std::vector<std::string> farArgs = {"--light-distance", "infinity"}, nearArgs = {"--light-distance", text};
  std::printf("\n%s: %s; %d threads, %d rounds\n", spec.name.c_str(), describe(spec.options).c_str(), settings.threads,
              rounds);
  for (int i = 0; i < rounds; ++i) {
    floors.push_back(runFloor(settings, capture));
    // In turns first: a machine whose load drifts does not favour one side.
    if (i % 2 == 0) {
      far.push_back(runSurrogate(settings, capture, farArgs));
      near.push_back(runSurrogate(settings, capture, nearArgs));
    } else {
      near.push_back(runSurrogate(settings, capture, nearArgs));
      far.push_back(runSurrogate(settings, capture, farArgs));
    }
    ok = ok && floors.back() > 0 && far.back().ok && near.back().ok;
    std::printf("  round %d: floor %.3f s, %s, %s\n", i + 1, floors.back(), roundCell("far", far.back()).c_str(),
                roundCell("near", near.back()).c_str());
  }
  printPair(summarise(far, floors), summarise(near, floors));
  return ok;
}

}  // namespace

int main(int argc, char** argv) {
  Settings settings;
  settings.threads = int(std::max(1u, std::thread::hardware_concurrency()));
  fs::path dir = fs::temp_directory_path() / "surrogate-run-shares";
  int rounds = kDefaultRounds;
  bool large = false, nearToo = true, usage = false;
  for (int i = 1; i < argc; ++i) {
    const std::string a = argv[i];
    if (a == "--large") large = true;
    else if (a == "--no-near") nearToo = false;
    else if (i + 1 >= argc) usage = true;
    else if (a == "--surrogate") settings.surrogate = argv[++i];
    else if (a == "--floor") settings.floor = argv[++i];
    else if (a == "--dir") dir = argv[++i];
    else if (a == "--rounds") rounds = std::atoi(argv[++i]);
    else if (a == "--threads") settings.threads = std::atoi(argv[++i]);
    else usage = true;
  }
  if (usage || settings.surrogate.empty() || settings.floor.empty() || rounds < 1 || settings.threads < 1) {
    std::fprintf(stderr, "usage: run_shares --surrogate PATH --floor PATH [--dir DIR] [--rounds N] [--threads N] "
                         "[--large] [--no-near]\n");
    return 2;
  }

  std::vector<CaptureSpec> farCaptures = {jpegCapture("small", 36, 1200, 800, kSmallSphereRadius)};
  if (large) farCaptures.push_back(jpegCapture("large", 60, 6000, 4000, 4000 / kLargeRadiusDivisor));
  CaptureSpec nearCapture = jpegCapture("near", 36, 1200, 800, kSmallSphereRadius);
  nearCapture.options.spheres = 2;  // a light's position needs two spheres
  nearCapture.options.lightDistance = kNearDistance;

  bool ok = true;
  try {
    for (const CaptureSpec& spec : farCaptures) ok = measureFar(settings, spec, prepare(dir, spec), rounds) && ok;
    if (nearToo) ok = measureNear(settings, nearCapture, prepare(dir, nearCapture), rounds) && ok;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "run_shares: %s\n", e.what());
    return 1;
  }
  return ok ? 0 : 1;
}
