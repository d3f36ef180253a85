// Private to src/fit: the per-channel linear fit shared by PTM RGB and HSH.
//
// For each pixel and colour channel c:  a_{c,k} = sum_i P[k][i] * s_i,c   (k < T)
// computed for a row at once, in blocks of kBlockSamples samples that stay in the L1 cache
// (loop over blocks, then terms, then lights, then the block's samples), so the compiler
// vectorises across pixels while each coefficient still sums the lights in order.
#pragma once

#include <cstdint>
#include <vector>

#include "fit/stream_fit.h"

namespace surrogate::fit {

class ChannelFitter : public RowFitter {
 public:
  // p: T x N in the model's units per 16-bit sample; basisAtLights: N x T;
  // displayScale: model value -> 0..255 (1 for PTM, 255 for HSH).
  ChannelFitter(std::vector<double> p, std::vector<double> basisAtLights, int n, int terms,
                double displayScale);

  int ranges() const override { return terms_; }
  int keptFloats() const override { return 3 * terms_; }
  std::size_t scratchDoubles(int width) const override;
  void measure(const RowView& row, double* scratch, double* lo, double* hi,
               float* kept) const override;
  void quantise(const RowView& row, double* scratch, double* sqErr,
                const float* kept) const override;

 protected:
  // Quantises coefficient k of row y, a[j] for the m = 3 width samples (pixel j / 3, channel
  // j % 3): stores the bytes in the result and writes their decoded values to decoded[j].
  virtual void quantiseRow(int k, int y, const double* a, std::size_t m,
                           double* decoded) const = 0;

 private:
  void fitRow(const RowView& row, double* acc) const;  // acc: T x (3 width)
  void measureError(const RowView& row, const double* decoded, double* pred,
                    double* sqErr) const;
  std::vector<double> p_, basis_;
  int n_, terms_;
  double displayScale_;
};

}  // namespace surrogate::fit
