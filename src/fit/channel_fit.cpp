#include "fit/channel_fit.h"

#include <algorithm>
#include <array>
#include <vector>

#include <Eigen/Core>

#include "fit/error_kernels.h"
#include "fit/near_fit.h"
#include "fit/row_kernels.h"

namespace surrogate::fit {

namespace {
// Samples per block: a multiple of 3 (whole pixels); a block of every photograph as doubles
// (36 x 192 x 8 bytes) stays in the cache next to the row's coefficients.
constexpr std::size_t kBlockSamples = kProductBlock;
static_assert(kBlockSamples % 3 == 0, "a block holds whole pixels");

using RowMajor = Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor>;
using Strided = Eigen::Map<RowMajor, 0, Eigen::OuterStride<>>;
}  // namespace

ChannelFitter::ChannelFitter(std::vector<double> p, std::vector<double> basisAtLights, int n,
                             int terms, double displayScale)
    : p_(std::move(p)), basis_(std::move(basisAtLights)), n_(n), terms_(terms),
      displayScale_(displayScale) {
  for (double b : basis_) basisF_.push_back(static_cast<float>(b));
}

std::size_t ChannelFitter::ownScratch(int width) const {
  const std::size_t row = static_cast<std::size_t>(width) * 3;
  // Coefficients, decoded coefficients, one N x kBlockSamples block (samples or re-rendering),
  // a row of quantised bytes.
  return 2 * terms_ * row + static_cast<std::size_t>(n_) * kBlockSamples + (row + 7) / 8;
}

std::size_t ChannelFitter::scratchDoubles(int width) const {
  return ownScratch(width) + (near_ ? near_->scratchDoubles(width) : 0);  // the near model's after ours
}

// coefficients (T x block) = P (T x N) * samples (N x block), block after block. Whole blocks
// go through multiplyBlock, which adds as Eigen's product does; the row's last, partial block
// stays with Eigen, which adds the last two or three samples of some lengths in another order
// (vectorised over the photographs), so that the models keep their bytes for every width.
void ChannelFitter::fitRow(const RowView& row, double* acc, double* block, double* nearScratch) const {
  if (near_) return near_->fitChannels(row, acc, nearScratch);
  const std::size_t m = static_cast<std::size_t>(row.width) * 3;
  const Eigen::Map<const RowMajor> p(p_.data(), terms_, n_);
  for (std::size_t j0 = 0; j0 < m; j0 += kBlockSamples) {
    const std::size_t len = std::min(kBlockSamples, m - j0);
    if (len == kBlockSamples) {
      withSamples(row, [&](auto images) { multiplyBlock(p_.data(), terms_, n_, images, j0, acc + j0, m); });
      continue;
    }
    Strided samples(block, n_, len, Eigen::OuterStride<>(kBlockSamples));
    withSamples(row, [&](auto images) {
      for (int i = 0; i < n_; ++i)
        for (std::size_t t = 0; t < len; ++t) block[i * kBlockSamples + t] = sampleValue(images[i][j0 + t]);
    });
    Strided(acc + j0, terms_, len, Eigen::OuterStride<>(m)).noalias() = p * samples;
  }
}

void ChannelFitter::measure(const RowView& row, double* scratch, double* lo, double* hi) const {
  const std::size_t m = static_cast<std::size_t>(row.width) * 3;
  fitRow(row, scratch, scratch + 2 * terms_ * m, scratch + ownScratch(row.width));
  for (int k = 0; k < terms_; ++k) rangeOf(scratch + k * m, m, &lo[k], &hi[k]);
  if (kept_) {
    float* to = kept_ + static_cast<std::size_t>(row.y) * terms_ * m;
    for (std::size_t j = 0; j < terms_ * m; ++j) to[j] = static_cast<float>(scratch[j]);
  }
}

void ChannelFitter::quantise(const RowView& row, double* scratch, double* sqErr) const {
  const std::size_t m = static_cast<std::size_t>(row.width) * 3;
  double* acc = scratch;
  double* decoded = scratch + terms_ * m;
  double* block = decoded + terms_ * m;
  auto* bytes = reinterpret_cast<std::uint8_t*>(block + static_cast<std::size_t>(n_) * kBlockSamples);
  // Rounded to float, as RtiFit version 2 kept them between the passes (fit.h).
  double* nearScratch = scratch + ownScratch(row.width);
  if (kept_) {
    const float* from = kept_ + static_cast<std::size_t>(row.y) * terms_ * m;
    for (std::size_t j = 0; j < terms_ * m; ++j) acc[j] = from[j];
  } else {
    fitRow(row, acc, block, nearScratch);
    for (std::size_t j = 0; j < terms_ * m; ++j) acc[j] = static_cast<float>(acc[j]);
  }
  for (int k = 0; k < terms_; ++k) {
    double* d = decoded + k * m;
    quantiseRow(k, row.y, acc + k * m, m, bytes, d);
    for (std::size_t j = 0; j < m; ++j) d[j] *= displayScale_;
  }
  measureError(row, decoded, block, nearScratch, sqErr);
}

// Re-renders the stored model at every captured light (N x block = basis (N x T) * decoded
// (T x block)) and compares luminance; each sqErr[i] still sums the pixels in row order.
void ChannelFitter::measureError(const RowView& row, const double* decoded, double* block,
                                 double* nearScratch, double* sqErr) const {
  const std::size_t m = static_cast<std::size_t>(row.width) * 3;
  const Eigen::Map<const RowMajor> basis(basis_.data(), n_, terms_);
  std::fill(sqErr, sqErr + n_, 0.0);
  if (near_) return near_->errorsChannels(row, decoded, nearScratch, sqErr);
  if (errors_ == ErrorMeasure::Lanes) return measureErrorSingle(row, decoded, sqErr);
  std::array<double, kBlockSamples / 3> d2;
  std::vector<const double*> decodedRows(terms_);
  for (int k = 0; k < terms_; ++k) decodedRows[k] = decoded + k * m;
  for (std::size_t j0 = 0; j0 < m; j0 += kBlockSamples) {
    const std::size_t len = std::min(kBlockSamples, m - j0);
    if (len == kBlockSamples) {  // as in fitRow
      multiplyBlock(basis_.data(), n_, terms_, decodedRows.data(), j0, block, kBlockSamples);
    } else {
      const Eigen::Map<const RowMajor, 0, Eigen::OuterStride<>> d(decoded + j0, terms_, len,
                                                                  Eigen::OuterStride<>(m));
      Strided(block, n_, len, Eigen::OuterStride<>(kBlockSamples)).noalias() = basis * d;
    }
    for (int i = 0; i < n_; ++i) {
      const double* p = block + static_cast<std::size_t>(i) * kBlockSamples;
      withSamples(row, [&](auto images) { squaredErrorsRgb(p, images[i] + j0, len / 3, d2.data()); });
      double err = sqErr[i];
      for (std::size_t x = 0; x < len / 3; ++x) err += d2[x];  // in pixel order, whichever kernel ran
      sqErr[i] = err;
    }
  }
}

// The errors in single precision (fit/error_kernels.h): the decoded coefficients copied to
// float planes, one per term and channel, a row's at a time.
void ChannelFitter::measureErrorSingle(const RowView& row, const double* decoded, double* sqErr) const {
  const std::size_t w = static_cast<std::size_t>(row.width), m = 3 * w;
  thread_local std::vector<float> copies;
  thread_local std::vector<const float*> planes;
  copies.resize(terms_ * m);
  planes.resize(3 * static_cast<std::size_t>(terms_));
  for (int k = 0; k < terms_; ++k)
    for (int c = 0; c < 3; ++c) {
      float* to = copies.data() + (3 * k + c) * w;
      const double* from = decoded + k * m + c;
      for (std::size_t x = 0; x < w; ++x) to[x] = static_cast<float>(from[3 * x]);
      planes[3 * k + c] = to;
    }
  for (int i = 0; i < n_; ++i)
    withSamples(row, [&](auto images) {
      sqErr[i] = channelSquaredErrorSum(planes.data(), terms_, &basisF_[static_cast<std::size_t>(i) * terms_], images[i], w);
    });
}

}  // namespace surrogate::fit
