#include "fit/channel_fit.h"

#include <algorithm>

namespace surrogate::fit {

namespace {
// Samples per block: a multiple of 3 (whole pixels); the block's samples of every photograph
// (36 x 192 x 2 bytes) and its accumulators stay in a 32 KiB L1 cache.
constexpr std::size_t kBlockSamples = 192;
}  // namespace

ChannelFitter::ChannelFitter(std::vector<double> p, std::vector<double> basisAtLights, int n,
                             int terms, double displayScale)
    : p_(std::move(p)), basis_(std::move(basisAtLights)), n_(n), terms_(terms),
      displayScale_(displayScale) {}

std::size_t ChannelFitter::scratchDoubles(int width) const {
  const std::size_t row = static_cast<std::size_t>(width) * 3;
  return 2 * terms_ * row + kBlockSamples;  // coefficients, decoded coefficients, prediction
}

void ChannelFitter::fitRow(const RowView& row, double* acc) const {
  const std::size_t m = static_cast<std::size_t>(row.width) * 3;
  for (std::size_t j0 = 0; j0 < m; j0 += kBlockSamples) {
    const std::size_t len = std::min(kBlockSamples, m - j0);
    for (int k = 0; k < terms_; ++k) {
      double* a = acc + k * m + j0;
      const double* p = &p_[static_cast<std::size_t>(k) * n_];
      std::fill(a, a + len, 0.0);
      for (int i = 0; i < n_; ++i) {
        const std::uint16_t* s = row.images[i] + j0;
        const double pi = p[i];
        for (std::size_t j = 0; j < len; ++j) a[j] += pi * s[j];
      }
    }
  }
}

void ChannelFitter::measure(const RowView& row, double* scratch, double* lo, double* hi,
                            float* kept) const {
  const std::size_t m = static_cast<std::size_t>(row.width) * 3;
  fitRow(row, scratch);
  for (int k = 0; k < terms_; ++k) {
    const double* a = scratch + k * m;
    lo[k] = *std::min_element(a, a + m);
    hi[k] = *std::max_element(a, a + m);
  }
  if (kept) std::copy(scratch, scratch + terms_ * m, kept);
}

void ChannelFitter::quantise(const RowView& row, double* scratch, double* sqErr,
                             const float* kept) const {
  const std::size_t m = static_cast<std::size_t>(row.width) * 3;
  double* acc = scratch;
  double* decoded = scratch + terms_ * m;
  double* pred = decoded + terms_ * m;
  if (kept) {
    std::copy(kept, kept + terms_ * m, acc);
  } else {  // the values pass 1 would have kept
    fitRow(row, acc);
    for (std::size_t j = 0; j < terms_ * m; ++j) acc[j] = static_cast<float>(acc[j]);
  }
  for (int k = 0; k < terms_; ++k) {
    double* d = decoded + k * m;
    quantiseRow(k, row.y, acc + k * m, m, d);
    for (std::size_t j = 0; j < m; ++j) d[j] *= displayScale_;
  }
  measureError(row, decoded, pred, sqErr);
}

// Re-renders the stored model at every captured light and compares luminance, block by block;
// each sqErr[i] still sums the pixels in row order.
void ChannelFitter::measureError(const RowView& row, const double* decoded, double* pred,
                                 double* sqErr) const {
  const std::size_t m = static_cast<std::size_t>(row.width) * 3;
  std::fill(sqErr, sqErr + n_, 0.0);
  for (std::size_t j0 = 0; j0 < m; j0 += kBlockSamples) {
    const std::size_t len = std::min(kBlockSamples, m - j0);
    for (int i = 0; i < n_; ++i) {
      std::fill(pred, pred + len, 0.0);
      for (int k = 0; k < terms_; ++k) {
        const double wk = basis_[static_cast<std::size_t>(i) * terms_ + k];
        const double* d = decoded + k * m + j0;
        for (std::size_t j = 0; j < len; ++j) pred[j] += wk * d[j];
      }
      const std::uint16_t* s = row.images[i] + j0;
      double err = sqErr[i];
      for (std::size_t x = 0; x < len / 3; ++x) {
        const double r = std::clamp(pred[3 * x], 0.0, 255.0);
        const double g = std::clamp(pred[3 * x + 1], 0.0, 255.0);
        const double b = std::clamp(pred[3 * x + 2], 0.0, 255.0);
        const double model = kLumR * r + kLumG * g + kLumB * b;
        const double captured =
            (kLumR * s[3 * x] + kLumG * s[3 * x + 1] + kLumB * s[3 * x + 2]) / 257.0;
        err += (model - captured) * (model - captured);
      }
      sqErr[i] = err;
    }
  }
}

}  // namespace surrogate::fit
