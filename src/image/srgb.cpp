#include "image/srgb.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <vector>

namespace surrogate::image {

// Built once (thread-safe static initialisation). std::pow on the same doubles gives the same
// result on a given platform, and rounding to 16 bits absorbs the last-ulp differences between
// libm versions for all but values sitting exactly on a rounding boundary.
const std::vector<std::uint16_t>& srgbEncodingTable() {
  static const std::vector<std::uint16_t> table = [] {
    std::vector<std::uint16_t> t(65536);
    for (int i = 0; i < 65536; ++i) {
      const double v = i / 65535.0;
      const double e = v <= 0.0031308 ? 12.92 * v : 1.055 * std::pow(v, 1.0 / 2.4) - 0.055;
      t[i] = static_cast<std::uint16_t>(std::lround(std::clamp(e, 0.0, 1.0) * 65535.0));
    }
    return t;
  }();
  return table;
}

Image srgbEncode(const Image& linear) {
  const std::vector<std::uint16_t>& table = srgbEncodingTable();
  Image out = linear;
  out.transfer = Transfer::Srgb;
  for (std::uint16_t& v : out.pixels) v = table[v];
  return out;
}

}  // namespace surrogate::image
