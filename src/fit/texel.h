// Private to src/fit: decoding the model of one texel, shared by normals and rendering.
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <vector>

#include "fit/ptm_math.h"
#include "formats/ptm.h"
#include "formats/rti_hsh.h"

namespace surrogate::fit {

// Decoded polynomial of channel c (Rgb) or the luminance polynomial (Lrgb; c ignored).
PtmCoefficients ptmChannel(const formats::PtmFile& ptm, int x, int y, int c);
// The polynomial that drives normals: Lrgb's luminance, or the mean of Rgb's three channels.
PtmCoefficients ptmLuminance(const formats::PtmFile& ptm, int x, int y);

// A PTM's coefficients decoded from their bytes, (byte - bias_k) scale_k as PtmFile::coefficient
// gives them, tabulated for the 256 byte values of each of the six.
class PtmDecoded {
 public:
  explicit PtmDecoded(const formats::PtmFile& ptm) {
    for (int k = 0; k < 6; ++k)
      for (int b = 0; b < kByteValues; ++b) value_[k][b] = (b - ptm.bias[k]) * ptm.scale[k];
  }
  // The polynomial whose six bytes start at `bytes` (ptmChannel).
  PtmCoefficients operator()(const std::uint8_t* bytes) const {
    PtmCoefficients a;
    for (int k = 0; k < 6; ++k) a[k] = value_[k][bytes[k]];
    return a;
  }

 private:
  static constexpr int kByteValues = 256;
  double value_[6][kByteValues];
};

// ptmLuminance's polynomial of the texel whose first channel's bytes start at `bytes`, channels
// `plane` bytes apart (Rgb), from `decoded`: the same values (inline: once a texel in loops).
inline PtmCoefficients ptmLuminance(const formats::PtmFile& ptm, const PtmDecoded& decoded,
                                    const std::uint8_t* bytes, std::size_t plane) {
  if (ptm.format == formats::PtmFile::Format::Lrgb) return decoded(bytes);
  PtmCoefficients a{};
  for (int c = 0; c < 3; ++c) {  // the mean of the channels, in their order
    const PtmCoefficients ac = decoded(bytes + c * plane);
    for (int k = 0; k < 6; ++k) a[k] += ac[k] / 3.0;
  }
  return a;
}

// Lambertian fit b (0..255 units) of a PTM polynomial (lambert.h).
std::array<double, 3> ptmLambert(const PtmCoefficients& a);

// Lambertian fit b_c (0..255 units) of each colour channel of an HSH texel.
void hshLambert(const formats::HshFile& hsh, int x, int y, std::array<double, 3> b[3]);

}  // namespace surrogate::fit
