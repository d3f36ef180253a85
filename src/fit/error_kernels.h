// Private to src/fit: the fit error of a stored model at one captured light, in single
// precision (RtiFit version 8 on; FitStatistics in fit/fit.h). Version 7 and earlier measured
// it in double precision, one squared error a pixel added up in pixel order
// (fit/row_kernels.h), and their records still re-execute that way (ErrorMeasure in fit/fit.h).
//
// Why single precision: re-rendering the model at every light and comparing it with the
// photograph was half of each fit's time (36 x 1200x800: 53 of 107 ms for ptm-lrgb, 65 of
// 132 ms for hsh2), held back by a chain of dependent double additions (the row's sum in pixel
// order) and by four doubles a vector. Eight floats a vector, summed in eight lanes, take a
// third of it. The model values are 0..255 and the errors a few levels, so float's 24-bit
// significand moves an image's RMSE by about a millionth of itself (1.2e-6 at most on the
// generated capture of bench/run_shares.cpp); the squares are still added in double.
//
// Each function returns, for pixels x < pixels of one row, the sum of d(x)^2 where every
// operation below is one IEEE-754 single-precision operation, left to right, no fused
// multiply-add:
//   LRGB         lum = basis[0] * L[0][x] + basis[1] * L[1][x] + ... + basis[5] * L[5][x]
//                v_c = C[c][x] * (lum * (1 / 255))                        c = R, G, B
//   per channel  v_c = basis[0] * P[c][x] + basis[1] * P[3 + c][x] + ... (terms of the
//                basis; P[3k + c] is term k of channel c)
//   both         model    = kLumR * clamp(v_R) + kLumG * clamp(v_G) + kLumB * clamp(v_B),
//                           clamp(v) = min(255, max(0, v)) (as std::clamp: NaN passes)
//                captured = (kLumR * R + kLumG * G + kLumB * B) * (1 / 257), R, G, B the 16-bit
//                           sample values (bytes b as 257 b), exact as floats
//                d        = model - captured
// The squares are added in double: pixel x, below the last multiple of 8, to lane x mod 8 in
// pixel order; the lanes then combine as ((l0 + l1) + (l2 + l3)) + ((l4 + l5) + (l6 + l7)),
// and the pixels past the last multiple of 8 are added to that in order. The baseline and the
// AVX2 variant evaluate exactly this, so their results are bit-identical on any machine
// (tests/fit/test_error_kernels.cpp).
//
//   lum[k]    = float planes of the decoded luminance coefficients (k < 6)
//   colour[c] = float planes of the stored colour bytes (c < 3)
//   sqErr[i] = lrgbSquaredErrorSum(lum, colour, basisAtLight_i, imageRow_i, width);
#pragma once

#include <cstddef>
#include <cstdint>

#include "fit/row_kernels.h"

namespace surrogate::fit {

double lrgbSquaredErrorSum(const float* const lum[6], const float* const colour[3], const float basis[6],
                           const std::uint16_t* s, std::size_t pixels, KernelIsa isa = activeKernelIsa());
double lrgbSquaredErrorSum(const float* const lum[6], const float* const colour[3], const float basis[6],
                           const std::uint8_t* s, std::size_t pixels, KernelIsa isa = activeKernelIsa());

// planes: 3 * terms planes, term k of channel c at planes[3 k + c]; basis: `terms` values.
double channelSquaredErrorSum(const float* const* planes, int terms, const float* basis, const std::uint16_t* s,
                              std::size_t pixels, KernelIsa isa = activeKernelIsa());
double channelSquaredErrorSum(const float* const* planes, int terms, const float* basis, const std::uint8_t* s,
                              std::size_t pixels, KernelIsa isa = activeKernelIsa());

}  // namespace surrogate::fit
