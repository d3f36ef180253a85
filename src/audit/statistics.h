// Private to src/audit: the order statistics and error figures the audit reports.
#pragma once

#include <algorithm>
#include <cmath>
#include <vector>

namespace surrogate::audit {

// The middle value (the mean of the two middle ones for an even count); 0 when empty.
inline double median(std::vector<double> v) {
  if (v.empty()) return 0;
  std::sort(v.begin(), v.end());
  const std::size_t n = v.size();
  return n % 2 ? v[n / 2] : 0.5 * (v[n / 2 - 1] + v[n / 2]);
}

// Nearest rank: the smallest value with at least a share q of the values at or below it.
inline double percentile(std::vector<double> v, double q) {
  if (v.empty()) return 0;
  std::sort(v.begin(), v.end());
  const auto rank = static_cast<std::size_t>(std::ceil(q * static_cast<double>(v.size())));
  return v[std::clamp<std::size_t>(rank, 1, v.size()) - 1];
}

// The cap of fit::FitStatistics: a perfect reproduction reads 100 dB, not infinity.
constexpr double kMaxPsnr = 100.0;

inline double psnrOf(double rmse) {
  return rmse <= 255.0 * std::pow(10.0, -kMaxPsnr / 20.0) ? kMaxPsnr : 20.0 * std::log10(255.0 / rmse);
}

}  // namespace surrogate::audit
