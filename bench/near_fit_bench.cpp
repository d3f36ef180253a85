// The fit under lights at known positions against the far-light fit (issue 53): wall time of
// fitPtm / fitHsh on the same photographs with FitOptions::nearLights empty and set, and the
// median error of the normals (fit::normalMap) against the rendered surface's own, in degrees:
// far fit, near fit, and the far fit of the same surface photographed under lights at infinity
// from the same directions (the bases' own error on it: what the near fit can reach).
//
// The photographs are rendered here (not timed): a Lambertian surface with normals varying across
// the frame (tilts up to 16 degrees) and a textured albedo, lit by N point lights on a spiral of
// elevations 20..80 degrees, D frame widths from the frame's centre, each pixel from its own
// direction with inverse-square fall-off; encoded as sRGB and held in memory as 8-bit samples, as
// decoded JPEG exports are.
//
//   near_fit_bench [--width 1200] [--height 800] [--images 36] [--distance 1.5] [--runs 5]
//                  [--threads 0]
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <ctime>
#include <string>
#include <vector>

#include "core/stack.h"
#include "fit/fit.h"
#include "fit/normals.h"

using namespace surrogate;
using Vec = std::array<double, 3>;

namespace {

// 8-bit RGB images held in memory (ImageStack::heldByteRow), as the decoded stacks hold JPEGs.
class ByteStack : public ImageStack {
 public:
  ByteStack(int w, int h, std::vector<std::vector<std::uint8_t>> images) : w_(w), h_(h), images_(std::move(images)) {}
  int size() const override { return static_cast<int>(images_.size()); }
  int width() const override { return w_; }
  int height() const override { return h_; }
  int channels() const override { return 3; }
  Transfer transfer() const override { return Transfer::Srgb; }
  void readRows(int index, int y0, int y1, std::uint16_t* out) const override {
    const std::uint8_t* src = images_[index].data() + static_cast<std::size_t>(y0) * w_ * 3;
    for (std::size_t j = 0; j < static_cast<std::size_t>(y1 - y0) * w_ * 3; ++j) out[j] = 257 * src[j];
  }
  const std::uint8_t* heldByteRow(int index, int y) const override {
    return images_[index].data() + static_cast<std::size_t>(y) * w_ * 3;
  }

 private:
  int w_, h_;
  std::vector<std::vector<std::uint8_t>> images_;
};

Vec normalAt(int x, int y, int w, int h) {
  const double gx = 0.2 * std::sin(2 * M_PI * x / w + 0.3), gy = 0.2 * std::cos(3 * M_PI * y / h);
  const double len = std::sqrt(gx * gx + gy * gy + 1);
  return {-gx / len, -gy / len, 1 / len};
}

double medianError(const Image& map) {
  std::vector<double> e;
  for (int y = 0; y < map.height; ++y)
    for (int x = 0; x < map.width; ++x) {
      const Vec t = normalAt(x, y, map.width, map.height);
      double dot = 0, len = 0;
      for (int c = 0; c < 3; ++c) {
        const double v = map.pixels[(static_cast<std::size_t>(y) * map.width + x) * 3 + c] / 65535.0 * 2 - 1;
        dot += v * t[c];
        len += v * v;
      }
      e.push_back(std::acos(std::clamp(dot / std::sqrt(len), -1.0, 1.0)) * 180 / M_PI);
    }
  std::nth_element(e.begin(), e.begin() + e.size() / 2, e.end());
  return e[e.size() / 2];
}

double seconds() {
  return std::chrono::duration<double>(std::chrono::steady_clock::now().time_since_epoch()).count();
}

}  // namespace

int main(int argc, char** argv) {
  int w = 1200, h = 800, n = 36, runs = 5, threads = 0;
  double d = 1.5;
  for (int i = 1; i + 1 < argc; i += 2) {
    const std::string a = argv[i];
    if (a == "--width") w = std::atoi(argv[i + 1]);
    else if (a == "--height") h = std::atoi(argv[i + 1]);
    else if (a == "--images") n = std::atoi(argv[i + 1]);
    else if (a == "--distance") d = std::atof(argv[i + 1]);
    else if (a == "--runs") runs = std::atoi(argv[i + 1]);
    else if (a == "--threads") threads = std::atoi(argv[i + 1]);
    else {
      std::fprintf(stderr, "near_fit_bench: unknown option %s (see the file's header)\n", a.c_str());
      return 2;
    }
  }
  std::vector<Vec> lights;
  std::vector<fit::NearLight> near;
  const double cx = (w - 1) / 2.0, cy = -(h - 1) / 2.0, r = d * w;
  for (int i = 0; i < n; ++i) {
    const double el = (20 + 60 * (i + 0.5) / n) * M_PI / 180, az = i * 2.399963229728653;
    lights.push_back({std::cos(el) * std::cos(az), std::cos(el) * std::sin(az), std::sin(el)});
    near.push_back({true, {cx + r * lights[i][0], cy + r * lights[i][1], r * lights[i][2]}, r});
  }
  // The photographs under the near lights, and (for the bases' own error on this surface) under
  // lights at infinity from the same directions.
  auto renderStack = [&](bool atInfinity) {
    std::vector<std::vector<std::uint8_t>> images(n, std::vector<std::uint8_t>(static_cast<std::size_t>(w) * h * 3));
    for (int i = 0; i < n; ++i) {
      const auto& X = near[i].position;
      for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x) {
          const double dx = atInfinity ? lights[i][0] : X[0] - x, dy = atInfinity ? lights[i][1] : X[1] + y;
          const double dz = atInfinity ? lights[i][2] : X[2];
          const double dist = std::sqrt(dx * dx + dy * dy + dz * dz);
          const double falloff = atInfinity ? 1.0 : (r / dist) * (r / dist);
          const Vec nn = normalAt(x, y, w, h);
          const double shade = std::max(0.0, (nn[0] * dx + nn[1] * dy + nn[2] * dz) / dist) * falloff;
          const double albedo = 0.35 + 0.1 * std::sin(x * 0.05) * std::cos(y * 0.07);
          const double colour[3] = {0.9, 0.7, 0.5};
          // Encoded as sRGB, as a JPEG export's values are (the fit then scales them in linear light).
          for (int c = 0; c < 3; ++c) {
            const double l = std::clamp(albedo * colour[c] * shade, 0.0, 1.0);
            const double v = l <= 0.0031308 ? 12.92 * l : 1.055 * std::pow(l, 1 / 2.4) - 0.055;
            images[i][(static_cast<std::size_t>(y) * w + x) * 3 + c] = static_cast<std::uint8_t>(std::lround(255 * v));
          }
        }
    }
    return ByteStack(w, h, std::move(images));
  };
  const ByteStack stack = renderStack(false);
  const ByteStack infinity = renderStack(true);
  std::printf("%d x %dx%d, lights %.2f frame widths away, %d runs (median), threads %d\n", n, w, h, d, runs, threads);
  std::printf("%-9s %7s %7s %5s %7s %7s %5s %8s %8s %8s\n", "basis", "far s", "near s", "ratio", "far cpu",
              "near cpu", "ratio", "far err", "near err", "inf err");
  for (fit::Basis b : {fit::Basis::PtmLrgb, fit::Basis::PtmRgb, fit::Basis::Hsh3}) {
    fit::FitOptions far;
    far.basis = b;
    far.threads = threads;
    fit::FitOptions nearOptions = far;
    nearOptions.nearLights = near;
    // Far and near alternate, so that a change of the machine's load hits both; wall and CPU
    // time (all threads), each the median of the runs.
    double errors[2] = {0, 0}, times[2] = {0, 0}, cpu[2] = {0, 0};
    std::vector<double> t[2], c[2];
    for (int run = 0; run < runs; ++run)
      for (int k = 0; k < 2; ++k) {
        const fit::FitOptions& o = k ? nearOptions : far;
        const double t0 = seconds();
        const std::clock_t c0 = std::clock();
        if (fit::isPtm(b)) {
          const auto m = fit::fitPtm(stack, lights, o);
          t[k].push_back(seconds() - t0);
          c[k].push_back(static_cast<double>(std::clock() - c0) / CLOCKS_PER_SEC);
          if (run == 0) errors[k] = medianError(fit::normalMap(m));
        } else {
          const auto m = fit::fitHsh(stack, lights, o);
          t[k].push_back(seconds() - t0);
          c[k].push_back(static_cast<double>(std::clock() - c0) / CLOCKS_PER_SEC);
          if (run == 0) errors[k] = medianError(fit::normalMap(m));
        }
      }
    for (int k = 0; k < 2; ++k) {
      std::sort(t[k].begin(), t[k].end());
      std::sort(c[k].begin(), c[k].end());
      times[k] = t[k][t[k].size() / 2];
      cpu[k] = c[k][c[k].size() / 2];
    }
    const double atInfinity = fit::isPtm(b) ? medianError(fit::normalMap(fit::fitPtm(infinity, lights, far)))
                                            : medianError(fit::normalMap(fit::fitHsh(infinity, lights, far)));
    std::printf("%-9s %7.3f %7.3f %5.2f %7.3f %7.3f %5.2f %8.2f %8.2f %8.2f\n", fit::basisName(b), times[0], times[1],
                times[1] / times[0], cpu[0], cpu[1], cpu[1] / cpu[0], errors[0], errors[1], atInfinity);
  }
  return 0;
}
