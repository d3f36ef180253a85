#include "core/image.h"

namespace surrogate {

Image luminance(const Image& in) {
  Image out(in.width, in.height, 1);
  out.bitsPerSample = in.bitsPerSample;
  out.transfer = in.transfer;
  const std::size_t n = static_cast<std::size_t>(in.width) * in.height;
  if (in.channels == 1) {
    out.pixels = in.pixels;
    return out;
  }
  // Weights 0.2126, 0.7152, 0.0722 in 1/65536 units (they sum to 65536 exactly).
  const std::uint32_t wr = 13933, wg = 46871, wb = 4732;
  for (std::size_t i = 0; i < n; ++i) {
    const std::uint16_t* p = &in.pixels[i * in.channels];
    const std::uint64_t v = wr * p[0] + wg * p[1] + wb * p[2];
    out.pixels[i] = static_cast<std::uint16_t>((v + 32768) >> 16);
  }
  return out;
}

}  // namespace surrogate
