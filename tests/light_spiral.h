// Test support shared by tests/fit and tests/audit: light directions spread evenly over a band
// of elevations and all azimuths.
#pragma once

#include <array>
#include <cmath>
#include <vector>

namespace surrogate::test {

// N unit lights on a golden-angle spiral: elevations from `lowDegrees` to `highDegrees` in N
// equal steps (taken at their middles), each azimuth 137.5 degrees on from the last.
inline std::vector<std::array<double, 3>> spiralLights(int n, double lowDegrees, double highDegrees) {
  std::vector<std::array<double, 3>> out;
  for (int i = 0; i < n; ++i) {
    const double el = (lowDegrees + (highDegrees - lowDegrees) * (i + 0.5) / n) * M_PI / 180.0;
    const double az = i * 2.399963229728653;
    out.push_back({std::cos(el) * std::cos(az), std::cos(el) * std::sin(az), std::sin(el)});
  }
  return out;
}

}  // namespace surrogate::test
