// Private to src/fit: the per-channel linear fit shared by PTM RGB and HSH.
//
// For each pixel and colour channel c:  a_{c,k} = sum_i P[k][i] * s_i,c   (k < T)
// computed for a row as matrix products, a block of samples at a time:
// coefficients (T x block) = P (T x N) * samples (N x block), where the block holds
// consecutive R, G, B samples of the row (kBlockSamples in channel_fit.cpp); the fit error
// re-renders the stored model the same way. Whole blocks go through fit::multiplyBlock
// (row_kernels.h), the row's last partial block through Eigen, whose sums they reproduce. Each
// row is computed alone with the same shapes, so the result does not depend on the thread count.
#pragma once

#include <cstdint>
#include <vector>

#include "fit/fit.h"
#include "fit/stream_fit.h"

namespace surrogate::fit {

class NearModel;

class ChannelFitter : public RowFitter {
 public:
  // p: T x N in the model's units per 16-bit sample; basisAtLights: N x T;
  // displayScale: model value -> 0..255 (1 for PTM, 255 for HSH).
  ChannelFitter(std::vector<double> p, std::vector<double> basisAtLights, int n, int terms,
                double displayScale);

  int ranges() const override { return terms_; }
  std::size_t scratchDoubles(int width) const override;
  void measure(const RowView& row, double* scratch, double* lo, double* hi) const override;
  void quantise(const RowView& row, double* scratch, double* sqErr) const override;
  std::size_t keptPerRow(int width) const override { return std::size_t(terms_) * width * 3; }
  void keep(float* rows) override { kept_ = rows; }
  // Lights at known positions: the rows are fitted and measured by `near` (fit/near_fit.h).
  void useNear(const NearModel* near) { near_ = near; }
  void measureErrorsIn(ErrorMeasure errors) { errors_ = errors; }

 protected:
  // Quantises coefficient k of row y, a[j] for the m = 3 width samples (pixel j / 3, channel
  // j % 3): stores the bytes in the result and writes their decoded values to decoded[j].
  // `bytes` is m bytes of scratch.
  virtual void quantiseRow(int k, int y, const double* a, std::size_t m, std::uint8_t* bytes,
                           double* decoded) const = 0;

 private:
  // acc: T x (3 width); block: N x kBlockSamples doubles of scratch.
  void fitRow(const RowView& row, double* acc, double* block, double* nearScratch) const;
  void measureError(const RowView& row, const double* decoded, double* block, double* nearScratch,
                    double* sqErr) const;
  void measureErrorSingle(const RowView& row, const double* decoded, double* sqErr) const;
  std::size_t ownScratch(int width) const;
  std::vector<double> p_, basis_;
  std::vector<float> basisF_;  // basis_ rounded to float, for the single-precision errors
  int n_, terms_;
  double displayScale_;
  const NearModel* near_ = nullptr;
  ErrorMeasure errors_ = ErrorMeasure::Lanes;
  float* kept_ = nullptr;  // pass 1's coefficients, rounded to float (RowFitter::keep)
};

}  // namespace surrogate::fit
