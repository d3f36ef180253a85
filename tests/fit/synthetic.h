// Test support: synthetic captures whose exact model is known. The photographs are computed
// FROM a per-pixel polynomial (or HSH expansion) at each light, so a least-squares fit must
// recover the coefficients up to the 16-bit rounding of the samples and the quantisation.
#pragma once

#include <array>
#include <cmath>
#include <random>
#include <vector>

#include "core/image.h"
#include "core/stack.h"
#include "fit/basis.h"
#include "reference_basis.h"
#include "../light_spiral.h"

namespace surrogate::test {

using Light = std::array<double, 3>;

// N lights spread over elevations 20..80 degrees and all azimuths (a golden-angle spiral).
inline std::vector<Light> spreadLights(int n) { return spiralLights(n, 20.0, 80.0); }

inline std::uint16_t sample255(double v) {  // 0..255 units -> 16-bit
  return static_cast<std::uint16_t>(std::lround(std::clamp(v, 0.0, 255.0) * 257.0));
}

// Exact PTM RGB model: coef[(y*w + x)*3 + c][k], values stay within 40..180 at any light.
struct PtmTruth {
  int w, h;
  std::vector<std::array<double, 6>> coef;
};

inline PtmTruth randomPtm(int w, int h, unsigned seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> u(0, 1);
  PtmTruth t{w, h, {}};
  for (int i = 0; i < w * h * 3; ++i) {
    t.coef.push_back({-30 * u(rng), -30 * u(rng), -8 + 16 * u(rng), -25 + 50 * u(rng),
                      -25 + 50 * u(rng), 110 + 30 * u(rng)});
  }
  return t;
}

// The photographs come from the closed forms of reference_basis.h, not from fit::ptmBasis /
// fit::hshBasis, so a fit that recovers the coefficients also checks the basis it fits with.
inline double evalPtm(const std::array<double, 6>& a, const Light& l) {
  const auto uv = reference::ptmArguments(l[0], l[1], l[2]);
  double v = 0;
  for (int k = 0; k < 6; ++k) v += a[k] * reference::ptmTerm(k, uv[0], uv[1]);
  return v;
}

inline MemoryImageStack ptmImages(const PtmTruth& t, const std::vector<Light>& lights) {
  std::vector<Image> images;
  for (const Light& l : lights) {
    Image im(t.w, t.h, 3);
    for (int p = 0; p < t.w * t.h * 3; ++p) im.pixels[p] = sample255(evalPtm(t.coef[p], l));
    images.push_back(std::move(im));
  }
  return MemoryImageStack(std::move(images));
}

// Exact HSH model in 0..1 units: coef[(y*w + x)*3 + c][k], values within 0.2..0.8.
struct HshTruth {
  int w, h, terms;
  std::vector<std::vector<double>> coef;
};

inline HshTruth randomHsh(int w, int h, int terms, unsigned seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> u(-1, 1);
  HshTruth t{w, h, terms, {}};
  for (int i = 0; i < w * h * 3; ++i) {
    std::vector<double> c(terms);
    c[0] = (0.5 + 0.1 * u(rng)) * std::sqrt(2 * M_PI);
    for (int k = 1; k < terms; ++k) c[k] = 0.03 * u(rng);
    t.coef.push_back(c);
  }
  return t;
}

inline double evalHsh(const std::vector<double>& c, const Light& l) {
  double v = 0;
  for (std::size_t k = 0; k < c.size(); ++k)
    v += c[k] * reference::hshTerm(static_cast<int>(k), l[0], l[1], l[2]);
  return v;
}

inline MemoryImageStack hshImages(const HshTruth& t, const std::vector<Light>& lights) {
  std::vector<Image> images;
  for (const Light& l : lights) {
    Image im(t.w, t.h, 3);
    for (int p = 0; p < t.w * t.h * 3; ++p)
      im.pixels[p] = sample255(255.0 * evalHsh(t.coef[p], l));
    images.push_back(std::move(im));
  }
  return MemoryImageStack(std::move(images));
}

}  // namespace surrogate::test
