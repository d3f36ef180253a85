// Decoding speed: the floor that later performance targets are ratios to.
//
// Generates one shot of WIDTHxHEIGHT (default 6000x4000, 24 Mpx) with the capture generator,
// writes it as a DNG (uncompressed 16-bit Bayer mosaic) and as a JPEG (quality 95), then
// decodes each RUNS times (default 5) and prints the median, min and max seconds.
//
//   decode_bench [--width W] [--height H] [--runs N] [--dir DIR]
#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <string>
#include <vector>

#include "generator/capture_generator.h"
#include "image/decode.h"

namespace fs = std::filesystem;
using namespace surrogate;

namespace {

struct Timing {
  double median, min, max;
};

template <typename F>
Timing timeRuns(int runs, F f) {
  std::vector<double> t;
  for (int i = 0; i < runs; ++i) {
    const auto t0 = std::chrono::steady_clock::now();
    f();
    t.push_back(std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count());
  }
  std::sort(t.begin(), t.end());
  return {t[t.size() / 2], t.front(), t.back()};
}

}  // namespace

int main(int argc, char** argv) {
  int width = 6000, height = 4000, runs = 5;
  fs::path dir = fs::temp_directory_path() / "surrogate-decode-bench";
  for (int i = 1; i + 1 < argc; i += 2) {
    const std::string a = argv[i];
    if (a == "--width") width = std::atoi(argv[i + 1]);
    else if (a == "--height") height = std::atoi(argv[i + 1]);
    else if (a == "--runs") runs = std::atoi(argv[i + 1]);
    else if (a == "--dir") dir = argv[i + 1];
  }
  fs::remove_all(dir);
  generator::GeneratorOptions options;
  options.width = width;
  options.height = height;
  options.images = 1;
  options.sphereRadius = std::min(width, height) / 10.0;
  std::printf("generating a %dx%d shot in %s ...\n", width, height, dir.c_str());
  generator::writeCapture(options, dir);
  const fs::path dng = dir / "original-captures/IMG_0001.dng";
  const fs::path jpg = dir / "jpeg-exports/IMG_0001.jpg";

  const image::RawDecodeSettings settings;
  const Timing raw = timeRuns(runs, [&] { image::decodeImage(dng, settings); });
  const Timing jpeg = timeRuns(runs, [&] { image::decodeImage(jpg, settings); });
  const double mpx = width * double(height) / 1e6;
  std::printf("decode %.1f Mpx, %d runs each (median / min / max seconds):\n", mpx, runs);
  std::printf("  DNG via %s (demosaic %s): %.3f / %.3f / %.3f  (%.1f Mpx/s)\n",
              image::librawVersion().c_str(), settings.demosaic.c_str(), raw.median, raw.min,
              raw.max, mpx / raw.median);
  std::printf("  JPEG via OpenCV %s:        %.3f / %.3f / %.3f  (%.1f Mpx/s)\n",
              image::opencvVersion().c_str(), jpeg.median, jpeg.min, jpeg.max, mpx / jpeg.median);
  fs::remove_all(dir);
  return 0;
}
