// Test support: a hand-made learned model (fit/learned.h) of either kind, 9 planes, 12 ring
// lights (3 decimals, as info.json holds them) or a 6 x 6 grid; smooth coefficients, so that
// JPEG at quality 100 keeps them to a level or two, and basis bytes that keep the relit values
// inside 0..1 and varied. Used by test_learned_layout and learned-layout-sample (the browser
// test's layouts).
//
//   fit::LearnedModel m = learnedsample::handMade(fit::LearnedKind::Rbf, 16, 12);
#pragma once

#include <cmath>

#include "fit/learned.h"

namespace learnedsample {

inline std::vector<std::array<double, 3>> ringLights() {
  std::vector<std::array<double, 3>> l;
  for (double e : {0.5, 1.0})
    for (int a = 0; a < 6; ++a) {
      const double phi = a * M_PI / 3 + e;
      l.push_back({std::round(1000 * std::cos(e) * std::cos(phi)) / 1000, std::round(1000 * std::cos(e) * std::sin(phi)) / 1000,
                   std::round(1000 * std::sin(e)) / 1000});
    }
  return l;
}

// `wave` scales the coefficients' spatial frequency (1 for 16 x 12; smaller for larger models).
inline surrogate::fit::LearnedModel handMade(surrogate::fit::LearnedKind kind, int width, int height, double wave = 1) {
  surrogate::fit::LearnedModel m;
  m.kind = kind;
  m.width = width;
  m.height = height;
  m.planes = 9;
  m.resolution = kind == surrogate::fit::LearnedKind::Bilinear ? 6 : 0;
  m.lights = ringLights();
  const int nodes = m.nodes();
  for (int p = 0; p <= m.planes; ++p)
    for (int n = 0; n < nodes; ++n)
      for (int k = 0; k < 3; ++k)
        m.basis.push_back(static_cast<std::uint8_t>(p == 0 ? 90 + (n * 37 + k * 53) % 100 : 87 + (n * 29 + p * 17 + k * 11) % 81));
  for (int p = 0; p < m.planes; ++p) {
    m.range.push_back(300.0f + 40.0f * p + 0.123456f);
    m.scale.push_back(1.5f - 0.1f * p + 1e-5f);
    m.bias.push_back(0.45f + 0.01f * p);
  }
  for (int y = 0; y < m.height; ++y)
    for (int x = 0; x < m.width; ++x)
      for (int p = 0; p < m.planes; ++p)
        m.coefficients.push_back(static_cast<std::uint8_t>(
            std::lround(128 + 70 * std::sin(wave * 0.3 * x + 0.7 * p) * std::cos(wave * 0.25 * y + 0.3 * p))));
  return m;
}

}  // namespace learnedsample
