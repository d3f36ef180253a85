#include "stages/chart_measurement.h"

#include <algorithm>
#include <cmath>

#include "stages/preprocess.h"

namespace surrogate::stages {

namespace {

// The line v = a e + b through the points with keep[i], least squares; false when the e's do
// not spread (a line is not determined).
bool fitLine(const std::vector<double>& e, const std::vector<double>& v, const std::vector<bool>& keep,
             double* a, double* b) {
  double n = 0, se = 0, sv = 0;
  for (std::size_t i = 0; i < e.size(); ++i)
    if (keep[i]) n += 1, se += e[i], sv += v[i];
  if (n < 2) return false;
  const double me = se / n, mv = sv / n;
  double see = 0, sev = 0;
  for (std::size_t i = 0; i < e.size(); ++i)
    if (keep[i]) see += (e[i] - me) * (e[i] - me), sev += (e[i] - me) * (v[i] - mv);
  if (see < 1e-6 * n) return false;
  *a = sev / see;
  *b = mv - *a * me;
  return true;
}

// The value at e = 1 of one patch's channel from its frames' (e, v); `used` gets how many
// frames the value rests on.
double valueAtNormal(const std::vector<double>& e, const std::vector<double>& v, int* used) {
  if (static_cast<int>(e.size()) >= kMinFramesForLine) {
    std::vector<bool> keep(e.size(), true);
    double a = 0, b = 0;
    if (fitLine(e, v, keep, &a, &b)) {
      std::vector<double> residuals;
      for (std::size_t i = 0; i < e.size(); ++i) residuals.push_back(std::abs(v[i] - (a * e[i] + b)));
      // 1.4826 MAD: the standard deviation of normal residuals; the floor keeps a perfect
      // line (generated, noise-free) from rejecting frames over rounding.
      const double limit = std::max(4 * 1.4826 * medianOf(residuals), 1e-4);
      int kept = 0;
      for (std::size_t i = 0; i < e.size(); ++i) kept += keep[i] = residuals[i] <= limit;
      if (kept >= kMinFramesForLine && fitLine(e, v, keep, &a, &b)) {
        *used = kept;
        return std::max(0.0, a + b);
      }
    }
  }
  std::vector<double> ratios;
  for (std::size_t i = 0; i < e.size(); ++i) ratios.push_back(v[i] / e[i]);
  *used = static_cast<int>(ratios.size());
  return medianOf(ratios);
}

}  // namespace

ChartMeasurement measureAtNormalIncidence(const std::vector<FrameReading>& frames) {
  ChartMeasurement m;
  for (const FrameReading& f : frames) m.framesUsable += f.usable;
  for (int k = 0; k < colour::kChartPatches; ++k) {
    std::vector<double> e;
    std::array<std::vector<double>, 3> v;
    for (const FrameReading& f : frames) {
      const colour::PatchReading& p = f.reading.patches[k];
      if (!f.usable || p.pixels == 0 || p.clipped > colour::kMaxClipped ||
          f.irradiance[k] < kMinIrradianceFactor)
        continue;
      e.push_back(f.irradiance[k]);
      for (int c = 0; c < 3; ++c) v[c].push_back(p.mean[c]);
    }
    PatchMeasurement& out = m.patches[k];
    if (e.empty()) continue;
    out.measured = true;
    out.frames = static_cast<int>(e.size());
    for (int c = 0; c < 3; ++c) {
      int used = 0;
      out.value[c] = valueAtNormal(e, v[c], &used);
      out.frames = std::min(out.frames, used);
    }
  }
  return m;
}

}  // namespace surrogate::stages
