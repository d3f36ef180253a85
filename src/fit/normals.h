// Surface normals and albedo recovered from a fitted model (.ptm or .rti HSH).
//
// PTM (docs/hrti-math.md, "Normals from a PTM"): the normal points at the maximum of the
// luminance polynomial (LRGB luminance; the mean of the channels for RGB):
//     d = 4 a0 a1 - a2^2;  lu0 = (a2 a4 - 2 a1 a3)/d;  lv0 = (a2 a3 - 2 a0 a4)/d
//     valid when d > 0 and a0 < 0;  (lu0, lv0) clamped to the unit disc;
//     n = (lu0, lv0, sqrt(1 - lu0^2 - lv0^2))
// Where there is no maximum, the FALLBACK is a least-squares Lambertian fit b = rho n of the
// polynomial's own values at 61 fixed directions (elevations 15..75 degrees every 15, 12
// azimuths, and the zenith): n = b/|b| (or (0, 0, 1) when b is 0 or faces away).
// HSH: the same Lambertian fit of the rendered luminance for every texel (there is no closed
// form); the fallback count is the number of texels left at (0, 0, 1).
// Albedo: the intensity a light along the normal would give: each channel's model evaluated at
// the normal above (LRGB: colour_c * L(n) / 255), in the model's own encoding. (Before
// DerivedMaps version 5 it was |b_c| of each channel's Lambertian fit, which for sRGB-encoded
// models is not that intensity: a Lambertian fit to encoded values overshoots it by ~15 %.)
//
// Encoding: normals as 16-bit RGB, value = round((n + 1) / 2 * 65535), x right, y UP, z towards
// the camera (the light convention), rows top-first, Transfer::Linear. Albedo as 8-bit sRGB.
//
//   int fallback = 0;
//   Image normals = normalMap(ptm, &fallback);   // then write it as a 16-bit PNG
//   Image albedo = albedoMap(ptm);
#pragma once

#include <array>

#include "core/image.h"
#include "fit/ptm_math.h"
#include "formats/ptm.h"
#include "formats/rti_hsh.h"

namespace surrogate::fit {

// Normal of one polynomial as described above; *usedFallback says whether the Lambertian
// fallback was used.
std::array<double, 3> ptmNormal(const PtmCoefficients& a, bool* usedFallback = nullptr);

Image normalMap(const formats::PtmFile& ptm, int* fallbackCount = nullptr, int threads = 0);
Image normalMap(const formats::HshFile& hsh, int* fallbackCount = nullptr, int threads = 0);
Image albedoMap(const formats::PtmFile& ptm, int threads = 0);
// normalMap and albedoMap of a PTM made in one pass, which finds each texel's normal once
// (about 15 ms of CPU of 1200x800 that the two maps made apart found twice).
void normalAndAlbedoMaps(const formats::PtmFile& ptm, Image* normals, Image* albedo, int* fallbackCount = nullptr,
                         int threads = 0);
Image albedoMap(const formats::HshFile& hsh, int threads = 0);

}  // namespace surrogate::fit
