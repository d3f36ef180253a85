// Speed and memory of the whole pipeline at full size (issues 3 and 4): 60 images of 24 Mpx.
//
// 1. Generates the capture once (JPEG exports only by default; --dng for DNG originals too),
//    kept in DIR between runs.
// 2. Decodes every image once, in this process, into the streaming stacks: the floor.
// 3. Runs `surrogate lights` (decode + light estimation) and `surrogate run` (decode, lights,
//    PTM LRGB, HSH order 2, derived maps) as child processes, measuring wall time and peak
//    resident memory (getrusage of the child).
// 4. Fits each basis alone with `surrogate fit` on the .lp that `lights` wrote.
// 5. With --light-distance D (frame widths; issue 53) the capture's lights are near, and the run
//    is made twice more: lights taken at infinity, and at the stated distance (each pixel its own
//    directions and fall-off): the near light's cost beside the far one's. (Closer than about 2
//    frame widths the far run refuses the far side's highlights as faint: use D = 3 for the ratio.)
// Prints each time and its ratio to the decode floor. Targets: lights below 2x decode (light
// estimation itself below 1x decode), the whole run within 1.5x of decode on JPEG input, peak
// memory under 2 GiB.
//
//   pipeline_bench --surrogate PATH [--dir DIR] [--images N] [--width W] [--height H] [--light-distance D]
#include <sys/resource.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <string>
#include <vector>

#include "generator/capture_generator.h"
#include "stages/decode_images.h"

namespace fs = std::filesystem;
using namespace surrogate;

namespace {

struct ChildRun {
  double seconds = 0;
  double peakMiB = 0;
  int status = -1;
};

ChildRun runChild(const std::vector<std::string>& args) {
  std::vector<char*> argv;
  for (const std::string& a : args) argv.push_back(const_cast<char*>(a.c_str()));
  argv.push_back(nullptr);
  const auto t0 = std::chrono::steady_clock::now();
  const pid_t pid = fork();
  if (pid == 0) {
    execv(argv[0], argv.data());
    _exit(127);
  }
  int status = 0;
  rusage usage{};
  wait4(pid, &status, 0, &usage);
  ChildRun r;
  r.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  r.peakMiB = usage.ru_maxrss / 1024.0;
  r.status = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  return r;
}

}  // namespace

int main(int argc, char** argv) {
  std::string surrogate;
  fs::path dir = fs::temp_directory_path() / "surrogate-pipeline-bench";
  generator::GeneratorOptions o;
  o.images = 60;
  o.width = 6000;
  o.height = 4000;
  o.sphereRadius = 300;
  o.formats = generator::OutputFormats::Jpeg;
  for (int i = 1; i < argc; ++i) {
    const std::string a = argv[i];
    if (a == "--dng") { o.formats = generator::OutputFormats::Both; continue; }
    if (i + 1 >= argc) break;
    if (a == "--surrogate") surrogate = argv[++i];
    else if (a == "--dir") dir = argv[++i];
    else if (a == "--images") o.images = std::atoi(argv[++i]);
    else if (a == "--width") o.width = std::atoi(argv[++i]);
    else if (a == "--height") o.height = std::atoi(argv[++i]);
    else if (a == "--light-distance") o.lightDistance = std::atof(argv[++i]);
  }
  if (surrogate.empty()) {
    std::fprintf(stderr, "usage: pipeline_bench --surrogate PATH [--dir DIR] [--images N] [--width W] [--height H] "
                         "[--light-distance D] [--dng]\n");
    return 2;
  }
  o.sphereRadius = std::min(o.width, o.height) / 13.0;
  const fs::path capture = dir / "capture";
  const fs::path stamp = dir / "generated.txt";
  const std::string want = std::to_string(o.images) + " " + std::to_string(o.width) + "x" + std::to_string(o.height) +
                           (o.formats == generator::OutputFormats::Jpeg ? " jpeg" : " both") +
                           (o.lightDistance > 0 ? " near " + std::to_string(o.lightDistance) : "");
  std::string have;
  if (FILE* f = std::fopen(stamp.c_str(), "r")) {
    char buffer[128] = {0};
    if (std::fgets(buffer, sizeof buffer, f)) have = buffer;
    std::fclose(f);
  }
  if (have != want) {
    fs::remove_all(dir);
    std::printf("generating %s in %s ...\n", want.c_str(), capture.c_str());
    std::fflush(stdout);
    const auto t0 = std::chrono::steady_clock::now();
    generator::writeCapture(o, capture);
    std::printf("  generated in %.1f s\n", std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count());
    FILE* f = std::fopen(stamp.c_str(), "w");
    std::fputs(want.c_str(), f);
    std::fclose(f);
  }
  std::vector<fs::path> files;
  for (const auto& e : fs::directory_iterator(capture / "jpeg-exports")) files.push_back(e.path());
  std::sort(files.begin(), files.end());

  const auto t0 = std::chrono::steady_clock::now();
  { const auto stacks = stages::decodeImages(files, image::RawDecodeSettings(), pipeline::RunSettings()); }
  const double decode = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  rusage self{};
  getrusage(RUSAGE_SELF, &self);
  const double mpx = double(o.width) * o.height / 1e6;
  std::printf("%d JPEG images of %.1f Mpx\n", o.images, mpx);
  std::printf("  decode once into the stacks: %8.1f s  (%.0f Mpixel-images/s, peak %.0f MiB)\n", decode,
              mpx * o.images / decode, self.ru_maxrss / 1024.0);
  std::fflush(stdout);

  fs::remove_all(capture / "assembly-files");
  fs::remove_all(capture / "finished-files");
  const ChildRun lights = runChild({surrogate, "lights", capture.string(), "-o", (dir / "lights.lp").string(), "--quiet", "--source", "export"});
  std::printf("  surrogate lights:            %8.1f s  (%.2fx decode; light estimation alone %.2fx) peak %.0f MiB%s\n",
              lights.seconds, lights.seconds / decode, (lights.seconds - decode) / decode, lights.peakMiB,
              lights.status == 0 ? "" : "  FAILED");
  std::fflush(stdout);
  // Each basis alone: `surrogate fit` decodes the images named by the .lp and fits one model,
  // so the fit itself is its time less the decode floor.
  const fs::path lp = capture / "assembly-files" / "lights.lp";
  if (lights.status == 0 && fs::exists(lp)) {
    for (const char* basis : {"ptm-lrgb", "ptm-rgb", "hsh2", "hsh3"}) {
      const std::string ext = std::string(basis).rfind("ptm", 0) == 0 ? ".ptm" : ".rti";
      const ChildRun fit = runChild({surrogate, "fit", "--lp", lp.string(), "-o",
                                     (dir / (std::string("bench-") + basis + ext)).string(), "--basis",
                                     basis, "--quiet"});
      const double fitOnly = std::max(1e-9, fit.seconds - decode);
      std::printf("  surrogate fit --basis %-8s %8.1f s  (%.2fx decode; fit alone %.1f s = %.0f Mpixel-images/s) peak %.0f MiB%s\n",
                  basis, fit.seconds, fit.seconds / decode, fitOnly, mpx * o.images / fitOnly, fit.peakMiB,
                  fit.status == 0 ? "" : "  FAILED");
      std::fflush(stdout);
    }
  }

  fs::remove_all(capture / "assembly-files");
  fs::remove_all(capture / "finished-files");
  const ChildRun run = runChild({surrogate, "run", capture.string(), "--quiet", "--source", "export"});
  std::printf("  surrogate run (ptm-lrgb, hsh2): %5.1f s  (%.2fx decode) peak %.0f MiB%s\n", run.seconds,
              run.seconds / decode, run.peakMiB, run.status == 0 ? "" : "  FAILED");
  bool nearOk = true;
  if (o.lightDistance > 0) {
    // The same run, lights at infinity and then at the stated distance, each from a clean start.
    double seconds[2] = {0, 0};
    char text[32];
    std::snprintf(text, sizeof text, "%g", o.lightDistance);
    const std::string stated = text;
    for (int k = 0; k < 2; ++k) {
      fs::remove_all(capture / "assembly-files");
      fs::remove_all(capture / "finished-files");
      const ChildRun r = runChild({surrogate, "run", capture.string(), "--quiet", "--source", "export", "--no-report",
                                   "--light-distance", k == 0 ? std::string("infinity") : stated});
      seconds[k] = r.seconds;
      nearOk = nearOk && r.status == 0;
      std::printf("  surrogate run --light-distance %-8s %5.1f s  (%.2fx decode) peak %.0f MiB%s\n",
                  k == 0 ? "infinity" : stated.c_str(), r.seconds, r.seconds / decode, r.peakMiB,
                  r.status == 0 ? "" : "  FAILED");
      std::fflush(stdout);
    }
    std::printf("  near run / far run: %.2f\n", seconds[1] / std::max(1e-9, seconds[0]));
  }
  return run.status == 0 && lights.status == 0 && nearOk ? 0 : 1;
}
