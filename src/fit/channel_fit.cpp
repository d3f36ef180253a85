#include "fit/channel_fit.h"

#include <algorithm>

namespace surrogate::fit {

ChannelFitter::ChannelFitter(std::vector<double> p, std::vector<double> basisAtLights, int n,
                             int terms, double displayScale)
    : p_(std::move(p)), basis_(std::move(basisAtLights)), n_(n), terms_(terms),
      displayScale_(displayScale) {}

std::size_t ChannelFitter::scratchDoubles(int width) const {
  const std::size_t row = static_cast<std::size_t>(width) * 3;
  return 2 * terms_ * row + row;  // coefficients, decoded coefficients, prediction
}

void ChannelFitter::fitRow(const RowView& row, double* acc) const {
  const std::size_t m = static_cast<std::size_t>(row.width) * 3;
  std::fill(acc, acc + terms_ * m, 0.0);
  for (int i = 0; i < n_; ++i) {
    const std::uint16_t* s = row.images[i];
    for (int k = 0; k < terms_; ++k) {
      const double p = p_[static_cast<std::size_t>(k) * n_ + i];
      double* a = acc + k * m;
      for (std::size_t j = 0; j < m; ++j) a[j] += p * s[j];
    }
  }
}

void ChannelFitter::measure(const RowView& row, double* scratch, double* lo, double* hi) const {
  const std::size_t m = static_cast<std::size_t>(row.width) * 3;
  fitRow(row, scratch);
  for (int k = 0; k < terms_; ++k) {
    const double* a = scratch + k * m;
    lo[k] = *std::min_element(a, a + m);
    hi[k] = *std::max_element(a, a + m);
  }
}

void ChannelFitter::quantise(const RowView& row, double* scratch, double* sqErr) const {
  const int w = row.width;
  const std::size_t m = static_cast<std::size_t>(w) * 3;
  double* acc = scratch;
  double* decoded = scratch + terms_ * m;
  double* pred = decoded + terms_ * m;
  fitRow(row, acc);
  for (int k = 0; k < terms_; ++k) {
    for (std::size_t j = 0; j < m; ++j) {
      const std::uint8_t b = quantiseValue(k, acc[k * m + j]);
      store(static_cast<int>(j / 3), row.y, static_cast<int>(j % 3), k, b);
      decoded[k * m + j] = decodeValue(k, b) * displayScale_;
    }
  }
  // Re-render the stored model at every captured light; compare luminance.
  for (int i = 0; i < n_; ++i) {
    std::fill(pred, pred + m, 0.0);
    for (int k = 0; k < terms_; ++k) {
      const double wk = basis_[static_cast<std::size_t>(i) * terms_ + k];
      const double* d = decoded + k * m;
      for (std::size_t j = 0; j < m; ++j) pred[j] += wk * d[j];
    }
    const std::uint16_t* s = row.images[i];
    double err = 0;
    for (int x = 0; x < w; ++x) {
      const double r = std::clamp(pred[3 * x], 0.0, 255.0);
      const double g = std::clamp(pred[3 * x + 1], 0.0, 255.0);
      const double b = std::clamp(pred[3 * x + 2], 0.0, 255.0);
      const double model = kLumR * r + kLumG * g + kLumB * b;
      const double captured = (kLumR * s[3 * x] + kLumG * s[3 * x + 1] + kLumB * s[3 * x + 2]) / 257.0;
      err += (model - captured) * (model - captured);
    }
    sqErr[i] = err;
  }
}

}  // namespace surrogate::fit
