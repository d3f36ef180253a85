// Accuracy of light estimation on generated captures with known truth (issue 3).
//
// For each case: generate a capture (samples/ generator), decode it as the pipeline does
// (DNG originals or JPEG exports), detect the spheres on the stack median, the highlights,
// and the light directions (orthographic; averaged over spheres, as the LightDirections
// stage does). Prints the sphere centre and radius errors (px) and the light angular error
// (median, 95th percentile, max, degrees). Targets (radius >= 60 px): centre <= 0.25 px,
// light median <= 0.3 deg, max <= 1.5 deg.
//
//   hrti_accuracy [--dir DIR] [--quick]
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <string>
#include <vector>

#include "core/error.h"
#include "generator/capture_generator.h"
#include "hrti/highlight_detection.h"
#include "hrti/light_direction.h"
#include "hrti/sphere_detection.h"
#include "hrti/stack_median.h"
#include "stages/decode_images.h"

namespace fs = std::filesystem;
using namespace surrogate;

namespace {

struct Case {
  const char* name;
  generator::GeneratorOptions options;
  bool useJpeg;
};

double percentile(std::vector<double> v, double p) {
  std::sort(v.begin(), v.end());
  return v[std::min(v.size() - 1, static_cast<std::size_t>(p * (v.size() - 1) + 0.5))];
}

}  // namespace

int main(int argc, char** argv) {
  fs::path dir = fs::temp_directory_path() / "surrogate-hrti-accuracy";
  bool quick = false;
  for (int i = 1; i < argc; ++i) {
    if (std::string(argv[i]) == "--dir" && i + 1 < argc) dir = argv[++i];
    if (std::string(argv[i]) == "--quick") quick = true;
  }
  auto base = [] {
    generator::GeneratorOptions o;
    o.images = 24;
    o.width = 1200;
    o.height = 800;
    o.sphereRadius = 80;
    o.seed = 17;
    return o;
  };
  std::vector<Case> cases;
  cases.push_back({"1 sphere, 24 images, r 80, DNG", base(), false});
  { auto o = base(); o.images = 60; cases.push_back({"1 sphere, 60 images, r 80, DNG", o, false}); }
  { auto o = base(); o.spheres = 2; cases.push_back({"2 spheres, 24 images, r 80, DNG", o, false}); }
  { auto o = base(); o.spheres = 2; o.images = 60; cases.push_back({"2 spheres, 60 images, r 80, DNG", o, false}); }
  { auto o = base(); o.strongTexture = true; cases.push_back({"strong background texture, DNG", o, false}); }
  { auto o = base(); o.noise = 600; cases.push_back({"heavy noise (600 DN), DNG", o, false}); }
  { auto o = base(); o.shadows = false; cases.push_back({"no cast shadows, DNG", o, false}); }
  { auto o = base(); o.jpegQuality = 95; cases.push_back({"JPEG exports, quality 95", o, true}); }
  { auto o = base(); o.jpegQuality = 75; cases.push_back({"JPEG exports, quality 75", o, true}); }
  { auto o = base(); o.sphereRadius = 30; cases.push_back({"sphere radius 30 px, DNG", o, false}); }
  { auto o = base(); o.sphereRadius = 150; o.width = 1600; o.height = 1200; cases.push_back({"sphere radius 150 px, DNG", o, false}); }
  if (quick) cases.resize(2);

  std::printf("%-34s %8s %8s %8s %8s %8s %7s\n", "case", "centre", "radius", "median", "p95", "max", "seconds");
  std::printf("%-34s %8s %8s %8s %8s %8s %7s\n", "", "err px", "err px", "deg", "deg", "deg", "");
  for (Case& c : cases) {
    const fs::path capture = dir / "capture";
    fs::remove_all(dir);
    c.options.formats = c.useJpeg ? generator::OutputFormats::Jpeg : generator::OutputFormats::Dng;
    generator::writeCapture(c.options, capture);
    const generator::CaptureTruth truth = generator::planCapture(c.options);
    std::vector<fs::path> files;
    for (int i = 0; i < c.options.images; ++i) {
      char name[64];
      std::snprintf(name, sizeof name, c.useJpeg ? "jpeg-exports/IMG_%04d.jpg" : "original-captures/IMG_%04d.dng", i + 1);
      files.push_back(capture / name);
    }
    const auto t0 = std::chrono::steady_clock::now();
    try {
      const stages::DecodedStacks stacks = stages::decodeImages(files, image::RawDecodeSettings(), pipeline::RunSettings());
      const hrti::SphereDetectionOptions detection;
      const hrti::StackMedian median(stacks.luminance, detection.coarseWidth, 0);
      const auto spheres = hrti::detectSpheres(median, detection);
      const auto highlights = hrti::detectHighlights(*stacks.luminance, spheres, hrti::HighlightOptions(), 0);
      const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
      double centreErr = 0, radiusErr = 0;
      for (const auto& t : truth.spheres) {
        double best = 1e9, rErr = 0;
        for (const auto& s : spheres) {
          const double d = std::hypot(s.cx - t.cx, s.cy - t.cy);
          if (d < best) {
            best = d;
            rErr = std::abs(s.r - t.r);
          }
        }
        centreErr = std::max(centreErr, best);
        radiusErr = std::max(radiusErr, rErr);
      }
      std::vector<double> errors;
      for (std::size_t i = 0; i < highlights.size(); ++i) {
        double sum[3] = {0, 0, 0};
        for (std::size_t k = 0; k < spheres.size(); ++k) {
          if (!hrti::isUsable(highlights[i][k].flag)) continue;
          const auto l = hrti::lightFromHighlight(spheres[k], highlights[i][k].x, highlights[i][k].y);
          sum[0] += l.x;
          sum[1] += l.y;
          sum[2] += l.z;
        }
        const double n = std::sqrt(sum[0] * sum[0] + sum[1] * sum[1] + sum[2] * sum[2]);
        const auto& t = truth.lights[i];
        errors.push_back(std::acos(std::min(1.0, (sum[0] * t[0] + sum[1] * t[1] + sum[2] * t[2]) / n)) * 180 / M_PI);
      }
      std::printf("%-34s %8.3f %8.3f %8.3f %8.3f %8.3f %7.2f%s\n", c.name, centreErr, radiusErr,
                  percentile(errors, 0.5), percentile(errors, 0.95), percentile(errors, 1.0), seconds,
                  spheres.size() == truth.spheres.size() ? "" : "  (sphere count differs!)");
    } catch (const Error& e) {
      std::printf("%-34s failed: %s\n", c.name, e.what());
    }
    std::fflush(stdout);
  }
  fs::remove_all(dir);
  return 0;
}
