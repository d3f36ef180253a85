// Private to src/fit: the per-pixel inverses of a fit under lights at known positions
// (fit/near_lights.h; the method is in fit.h, the formulas and the error bound in
// docs/hrti-math.md, "Near lights in the fit").
//
// The exact inverse P (T x N; the fit's scale folded in) and the basis at the lights B (T x N,
// for re-rendering; LRGB also the chroma weights, N) are computed at NODES every G pixels,
// (gx G, gy G), from the node's own light directions, and interpolated bilinearly in between:
// first along y for the row (each node column), then along x for the pixel,
//     R_c = N(gy, c) + v (N(gy + 1, c) - N(gy, c)),   v = (y - gy G) / G
//     M(x) = R_c + t (R_{c+1} - R_c),                 t = (x - c G) / G
// The fall-off factors f_i = ((X_i - x)^2 + (Y_i + y)^2 + Z_i^2) / r_i^2 are exact per pixel
// and multiply the samples. Every value depends on (x, y) alone, so the result does not depend
// on bands or threads. The loops are compiled twice (baseline and AVX2 without FMA, like
// row_kernels.h) with the same operations in the same order, so both give the same bits; the
// sRGB fall-off's blocks have AVX2 variants of their own (near_srgb_blocks.h), lane by lane the
// scalar operations.
#pragma once

#include <array>
#include <cstdint>
#include <vector>

#include "fit/conditioning.h"
#include "fit/fit.h"
#include "fit/row_kernels.h"
#include "fit/stream_fit.h"

namespace surrogate::fit {

// Checks options.nearLights against the lights (Error(Input) naming the light); true when at
// least one light is near (otherwise the far fit runs, with its bytes).
bool hasNearLights(const std::vector<std::array<double, 3>>& lights, const FitOptions& options);

// The node spacing G for a W x H stack: from the closest approach d of a near light to the frame,
// G = clamp(floor(d / 48), 2, 64) (docs/hrti-math.md gives the measured bound).
int nearNodeSpacing(int width, int height, const std::vector<NearLight>& near);

class NearModel {
 public:
  // `lights`: normalised directions (those of far lights are used as they are); `scale`
  // multiplies P (the fit's units per 16-bit sample); `spacing` G (1: an exact inverse at every
  // pixel). The conditioning is the far fit's rule at every node with one weight for the frame:
  // the largest any node's own light matrix asks for.
  // `transfer`: the samples' encoding. The fall-off is light, so sRGB samples are scaled in
  // linear light and encoded again (srgbScaled below); linear samples are multiplied.
  NearModel(int width, int height, const std::vector<std::array<double, 3>>& lights,
            const std::vector<NearLight>& near, Basis basis, double scale, int spacing, int threads,
            Transfer transfer = Transfer::Linear);

  const Conditioning& conditioning() const { return summary_; }  // worst node; weight used
  std::size_t bytes() const { return nodes_.size() * sizeof(double); }
  std::size_t scratchDoubles(int width) const;
  int spacing() const { return g_; }
  // The inverse the kernels use at pixel (x, y): T x N, scaled, as interpolated (for tests).
  std::vector<double> pixelInverse(int x, int y) const;

  // Per channel (PTM RGB, HSH): acc[k * 3w + 3x + c], the fitted coefficients of the row.
  // Each takes the kernel variant (row_kernels.h); both give the same bits.
  void fitChannels(const RowView& row, double* acc, double* scratch, KernelIsa isa = activeKernelIsa()) const;
  // sqErr[i] += sum over the row (as measureErrorsIn says) of the squared luminance error at light i of
  // the decoded model (decoded[k * 3w + 3x + c], 0..255 units) re-rendered at the pixel's own
  // direction, divided by f_i, clamped to 0..255.
  void errorsChannels(const RowView& row, const double* decoded, double* scratch, double* sqErr,
                      KernelIsa isa = activeKernelIsa()) const;
  // LRGB: acc[k * w + x] += sum_i P_ki f_i (R + G + B)_i, mean[3x + c] += sum_i w_i f_i s_ic.
  void fitLrgb(const RowView& row, double* acc, double* mean, double* scratch,
               KernelIsa isa = activeKernelIsa()) const;
  // LRGB errors: the colour bytes in planes cr, cg, cb; decoded[k * w + x].
  // How both add up a light's squares (fit.h): in pixel order (Serial, RtiFit version 7) or
  // each block's in eight lanes (Lanes, the default).
  void measureErrorsIn(ErrorMeasure errors) { errors_ = errors; }
  void errorsLrgb(const RowView& row, const double* cr, const double* cg, const double* cb,
                  const double* decoded, double* scratch, double* sqErr, KernelIsa isa = activeKernelIsa()) const;

 private:
  struct Row;
  Row startRow(int y, double* scratch, bool basis) const;
  int n_, terms_, g_, cols_, rows_;
  bool lrgb_;
  std::size_t stride_;                 // doubles per node: P, B (T x N each), weights (N, LRGB)
  std::vector<double> nodes_;          // rows_ x cols_ x stride_
  std::vector<double> x_, yz_, inv_;   // per light: X, (Y, Z), 1 / r^2; inv_ = 0 for far lights
  std::vector<std::uint8_t> near_;
  bool srgb_ = false;
  ErrorMeasure errors_ = ErrorMeasure::Lanes;
  Conditioning summary_;
};

// The fall-off on sRGB-encoded values (IEC 61966-2-1: v = 1.055 L^(1/2.4) - 0.055, L <= 0.0031308:
// 12.92 L), the same way for every pixel: decoding a 16-bit value is a table of 65536 exact
// values; decoding a model's value (0..255 units) and encoding (against sqrt(L)) are tables of
// 4097 exact values, interpolated linearly (error under 2e-6 of full scale), with the formula
// past their range (linear light 8, four times full scale encoded). Exposed for tests.
//   srgbScaled(v, f)      65535 E(D(v / 65535) f)   a 16-bit sample v lit f times as much
//   srgbUnscaled(m, g)    255 E(D(m / 255) g)       a model value m (0..255 units) lit g times
double srgbScaled(unsigned v16, double f);
double srgbUnscaled(double m255, double g);

// The fits with the node spacing forced (for tests: 1 = the exact per-pixel inverse).
formats::PtmFile fitPtmSpaced(const ImageStack& stack, const std::vector<std::array<double, 3>>& lights,
                              const FitOptions& options, int spacing, FitStatistics* stats);
formats::HshFile fitHshSpaced(const ImageStack& stack, const std::vector<std::array<double, 3>>& lights,
                              const FitOptions& options, int spacing, FitStatistics* stats);

}  // namespace surrogate::fit
