// Private to src/fit: the PTM normals of a row of texels at once, shared by the normal and
// albedo maps (fit/normals.cpp) and the specular render (fit/render.cpp).
#pragma once

#include <cstddef>
#include <cstdint>
#include <vector>

#include "fit/texel.h"
#include "formats/ptm.h"

namespace surrogate::fit {

// One row's luminance polynomials (ptmLuminance) and their normals (ptmNormal), as rows of
// doubles: lum[k][x] is a_k of texel x, n[c][x] its normal's component c.
struct PtmNormalRow {
  explicit PtmNormalRow(int width);
  std::vector<double> lum[6];
  std::vector<double> n[3];
  // Fills the row `y` of `ptm`; returns the number of texels that took the Lambertian fallback.
  int fill(const formats::PtmFile& ptm, const PtmDecoded& decoded, std::size_t plane, int y);

 private:
  std::vector<std::uint8_t> maximum_;  // per texel: 1 where the polynomial's maximum gave the normal
};

}  // namespace surrogate::fit
