// Private to src/fit: decoding the model of one texel, shared by normals and rendering.
#pragma once

#include <array>
#include <vector>

#include "fit/ptm_math.h"
#include "formats/ptm.h"
#include "formats/rti_hsh.h"

namespace surrogate::fit {

// Decoded polynomial of channel c (Rgb) or the luminance polynomial (Lrgb; c ignored).
PtmCoefficients ptmChannel(const formats::PtmFile& ptm, int x, int y, int c);
// The polynomial that drives normals: Lrgb's luminance, or the mean of Rgb's three channels.
PtmCoefficients ptmLuminance(const formats::PtmFile& ptm, int x, int y);

// Lambertian fit b (0..255 units) of a PTM polynomial (lambert.h).
std::array<double, 3> ptmLambert(const PtmCoefficients& a);

// Lambertian fit b_c (0..255 units) of each colour channel of an HSH texel.
void hshLambert(const formats::HshFile& hsh, int x, int y, std::array<double, 3> b[3]);

}  // namespace surrogate::fit
