// Private to src/fit: the per-channel linear fit shared by PTM RGB and HSH.
//
// For each pixel and colour channel c:  a_{c,k} = sum_i P[k][i] * s_i,c   (k < T)
// computed for a whole row at once (loop over lights, then terms, then the row's samples), so
// the compiler vectorises across pixels while each coefficient still sums the lights in order.
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
  std::size_t scratchDoubles(int width) const override;
  void measure(const RowView& row, double* scratch, double* lo, double* hi) const override;
  void quantise(const RowView& row, double* scratch, double* sqErr) const override;

 protected:
  // Byte for coefficient k with value a; its decoded value; where to store it.
  virtual std::uint8_t quantiseValue(int k, double a) const = 0;
  virtual double decodeValue(int k, std::uint8_t byte) const = 0;
  virtual void store(int x, int y, int c, int k, std::uint8_t byte) const = 0;

 private:
  void fitRow(const RowView& row, double* acc) const;  // acc: T x (3 width)
  std::vector<double> p_, basis_;
  int n_, terms_;
  double displayScale_;
};

}  // namespace surrogate::fit
