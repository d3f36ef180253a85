// refineRim's radial profiles (hrti/rim_fit.h): the AVX2 variant gives the plain one's bits, on
// random gradients and rays that start inside the window and leave it (NaN there), at distance
// counts that are not multiples of four, and on pixel borders exactly.
#include <catch2/catch.hpp>

#include <cmath>
#include <cstring>
#include <random>
#include <vector>

#include "core/cpu_features.h"
#include "hrti/rim_fit.h"

using namespace surrogate::hrti;

TEST_CASE("rim profiles: the AVX2 variant gives the plain one's bits") {
  if (!surrogate::cpuHasAvx2()) return;
  std::mt19937 rng(61);
  std::uniform_real_distribution<float> value(-2.0f, 2.0f);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  const int cols = 37, rows = 29, x0 = 100, y0 = 40;
  std::vector<float> gx(static_cast<std::size_t>(cols) * rows), gy(gx.size());
  for (std::size_t i = 0; i < gx.size(); ++i) gx[i] = value(rng), gy[i] = value(rng);
  const detail::RimGradients g{gx.data(), gy.data(), cols, rows, x0, y0};
  int compared = 0, nans = 0;
  for (int trial = 0; trial < 400; ++trial) {
    // A centre inside the window (on a pixel in a quarter of the trials), a ray in any direction
    // or along an axis.
    double cx = x0 + cols * unit(rng), cy = y0 + rows * unit(rng);
    if (trial % 4 == 0) cx = std::floor(cx), cy = std::floor(cy);
    const double a = trial % 5 == 0 ? M_PI / 2 * (trial % 4) : 2 * M_PI * unit(rng);
    const double ca = std::cos(a), sa = std::sin(a);
    const double margin = 1 + 10 * unit(rng), r = 20 * unit(rng);
    std::vector<double> ts;
    for (double t = r - margin; t <= r + margin; t += 0.25) ts.push_back(t);
    std::vector<double> plain(ts.size()), avx2(ts.size());
    detail::radialProfilePlain(g, cx, cy, ca, sa, ts.data(), ts.size(), plain.data());
    REQUIRE(detail::radialProfileAvx2(g, cx, cy, ca, sa, ts.data(), ts.size(), avx2.data()));
    REQUIRE(std::memcmp(plain.data(), avx2.data(), plain.size() * sizeof(double)) == 0);
    for (double v : plain) nans += std::isnan(v);
    compared += static_cast<int>(plain.size());
  }
  // Both cases were met: values inside the window and NaN outside it.
  CHECK(nans > 100);
  CHECK(compared - nans > 1000);
}
