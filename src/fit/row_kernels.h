// Private to src/fit: the per-pixel loops that bound the fits' time: the LRGB accumulation
// (every photograph's samples into the six luminance coefficients and the mean colour), the
// per-channel fits' block products, the quantisation of coefficients to bytes, and the error
// measurement (re-rendering the stored model at a captured light and comparing Rec. 709
// luminance with the photograph) as RtiFit version 7 and earlier made it, and lights at known
// positions still do; version 8's is in single precision (fit/error_kernels.h).
//
// These loops are bound by arithmetic (division, for the errors: four per pixel and light for
// LRGB), and the baseline x86-64 instruction set works on two doubles at once where AVX2 works
// on four. So each loop has two variants, for the baseline and for AVX2 without FMA (the same
// body compiled twice, or, for the accumulation, the block products, the ranges and the
// quantisation, an AVX2 variant written with intrinsics), and the variant is chosen once at run
// time. Both evaluate the same IEEE-754 operations in the same
// order for each value (no fused multiply-add, no reassociation, sums over photographs in
// photograph order), and the error kernels write one squared error per pixel, leaving the sum
// over the row to the caller, in pixel order. The results are therefore bit-identical whichever
// variant runs, on any machine; tests/fit/test_row_kernels.cpp compares the two.
//
//   std::vector<double> d2(width);
//   squaredErrorsLrgb(cr, cg, cb, decoded, width, basisAtLight, row, width, d2.data());
//   for (double v : d2) err += v;   // in order
#pragma once

#include <cstddef>
#include <cstdint>

#include "fit/quantise.h"

namespace surrogate::fit {

enum class KernelIsa { Baseline, Avx2 };

// The variant this machine runs: Avx2 where the processor has it.
KernelIsa activeKernelIsa();

// Samples come as 16-bit values or, where the photographs are held at 8 bits, as bytes b that
// stand for the 16-bit values 257 b (core/image.h widenSamples): every kernel taking samples has
// both forms, and gives the same bits for bytes as for their 16-bit values.
inline unsigned sampleValue(std::uint16_t s) { return s; }
inline unsigned sampleValue(std::uint8_t b) { return 257u * b; }

// LRGB accumulation over pixels [x0, x1) of a row of n photographs (images[i]: 16-bit
// interleaved RGB): for each photograph i in order, with S = R + G + B of the pixel,
//   acc[k * w + x] += p[k * n + i] * S   (k < 6),
//   mean[3 x + c] += weight[i] * sample_c  (skipped where weight[i] is 0).
// `sum` is w doubles of scratch.
void accumulateLrgb(const std::uint16_t* const* images, int n, std::size_t w, std::size_t x0, std::size_t x1,
                    const double* p, const double* weight, double* acc, double* mean, double* sum,
                    KernelIsa isa = activeKernelIsa());
void accumulateLrgb(const std::uint8_t* const* images, int n, std::size_t w, std::size_t x0, std::size_t x1,
                    const double* p, const double* weight, double* acc, double* mean, double* sum,
                    KernelIsa isa = activeKernelIsa());

// LRGB: d2[x] = (model - captured)^2 for pixels x < `pixels`, where
//   lum      = sum over k < 6, in order from 0, of basis[k] * decoded[k * stride + x] (the stored
//              luminance polynomial at the light),
//   model    = sum over c of kLum[c] * clamp(chroma_c[x] * lum / 255, 0, 255) (the colour bytes
//              as doubles in three planes cr, cg, cb),
//   captured = (kLumR R + kLumG G + kLumB B) / 257 of the 16-bit interleaved samples s.
void squaredErrorsLrgb(const double* cr, const double* cg, const double* cb, const double* decoded,
                       std::size_t stride, const double* basis, const std::uint16_t* s, std::size_t pixels,
                       double* d2, KernelIsa isa = activeKernelIsa());
void squaredErrorsLrgb(const double* cr, const double* cg, const double* cb, const double* decoded,
                       std::size_t stride, const double* basis, const std::uint8_t* s, std::size_t pixels,
                       double* d2, KernelIsa isa = activeKernelIsa());

// Per channel (PTM RGB, HSH): the same with model = sum over c of kLum[c] * clamp(rendered[3x +
// c], 0, 255), the rendered model interleaved like the samples.
void squaredErrorsRgb(const double* rendered, const std::uint16_t* s, std::size_t pixels, double* d2,
                      KernelIsa isa = activeKernelIsa());
void squaredErrorsRgb(const double* rendered, const std::uint8_t* s, std::size_t pixels, double* d2,
                      KernelIsa isa = activeKernelIsa());

// The matrix products of the per-channel fits (PTM RGB, HSH; fit/channel_fit.h), a block of
// kProductBlock samples at a time:
//   out[r * outStride + j] = 0 + (sum over c < cols, in order from c = 0 and from +0, of
//                                 m[r * cols + c] * src[c][offset + j])
// for r < rows and j < kProductBlock. Fitting: m = P (T x N), src = the photographs' rows;
// re-rendering: m = the basis at the lights (N x T), src = the rows of decoded coefficients.
// This is how Eigen's matrix product adds up a whole block (each value's terms in order into an
// accumulator started at zero, then added to the zeroed destination), which the fits used
// before and whose bytes these keep; tests/fit/test_row_kernels.cpp checks both variants
// against the formula. The AVX2 variant is written with intrinsics: the compiler's own
// vectorisation of the loops ran at about Eigen's speed, the intrinsics two to three times
// faster (docs/developer-guide.md, "Benchmarks").
constexpr std::size_t kProductBlock = 192;
void multiplyBlock(const double* m, int rows, int cols, const std::uint16_t* const* src, std::size_t offset,
                   double* out, std::size_t outStride, KernelIsa isa = activeKernelIsa());
void multiplyBlock(const double* m, int rows, int cols, const std::uint8_t* const* src, std::size_t offset,
                   double* out, std::size_t outStride, KernelIsa isa = activeKernelIsa());
void multiplyBlock(const double* m, int rows, int cols, const double* const* src, std::size_t offset,
                   double* out, std::size_t outStride, KernelIsa isa = activeKernelIsa());

// The range of a row of coefficients (count > 0): *lo = *std::min_element(a, a + count) and
// *hi = *std::max_element(a, a + count), bit for bit. Without NaN the result is the first
// element equal to the smallest (largest) value, and every element equal to it has its bits
// unless it is zero (+0 and -0 compare equal): the AVX2 variant takes the extremes four lanes
// at a time, then looks up the first zero where the extreme is zero, and leaves rows with NaN to
// the standard algorithms, whose answer then depends on where the NaN stands.
void rangeOf(const double* a, std::size_t count, double* lo, double* hi, KernelIsa isa = activeKernelIsa());

// Quantisation of `count` coefficients (fit/quantise.h): bytes[j] = q.quantise(a[j]) and
// decoded[j] = q.decode(bytes[j]).
void quantisePtm(const double* a, std::size_t count, const PtmQuantisation& q, std::uint8_t* bytes, double* decoded,
                 KernelIsa isa = activeKernelIsa());
void quantiseHsh(const double* a, std::size_t count, const HshQuantisation& q, std::uint8_t* bytes, double* decoded,
                 KernelIsa isa = activeKernelIsa());

}  // namespace surrogate::fit
