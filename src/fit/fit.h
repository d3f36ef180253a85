// PtmFit and HshFit: per-pixel least-squares fits of a capture's photographs against their
// light directions, quantised into .ptm / .rti objects (src/formats).
//
// For N photographs with unit light vectors l_i and a basis w(l) of T terms (fit/basis.h):
//
//     A = [ w(l_1); ...; w(l_N) ]            N x T, one row per light
//     P = (A^T A)^-1 A^T                     T x N, once per light set (SVD, double); its
//                                            damped form when the lights leave terms too
//                                            alike for 8-bit planes (fit/conditioning.h)
//     a = P s                                per pixel and channel, s = the N samples
//
// Units: samples are 16-bit (Image convention); the fit treats value/257 as 0..255 units
// (PTM coefficients, 0..255) or value/65535 as 0..1 units (HSH). The values are fitted as
// encoded (sRGB exports, docs/formats.md "Which pixel values are fitted"); no linearisation.
// LRGB (docs/formats.md "LRGB: colour and luminance", relight's): chroma = mean colour weighted by
// w_i = max(0, 0.25 - (asin(lz_i)/(pi/2) - 0.5)^2) (uniform weights if all are 0), stored as
// bytes C; luminance samples L_i = 255 (R_i + G_i + B_i) / (C_R + C_G + C_B) using the STORED
// bytes, so colour * L / 255 reproduces each photograph's R+G+B exactly before quantisation.
// A pixel whose stored chroma is black (0, 0, 0) renders black whatever L is: its L
// coefficients are set to 0 so that it does not widen the quantisation range.
//
// Streaming and memory: the photographs are read in row bands (ImageStack::readRows), all N
// images' rows of a band at once, unless the stack holds its RGB rows in memory
// (ImageStack::heldRow, heldByteRow): then each row is read where it is, 8-bit sources as their
// bytes, with no band buffer and no copy. The band height is the largest that keeps the band buffers
// within 8 MiB and, with the result object (9 or 18 bytes per pixel for PTM, 3*T for HSH) and
// the per-thread scratch, within FitOptions::memoryBudgetBytes (at least one row); rows held in
// memory go in bands of at least 1/32 of the height, the steps of the progress bar. Rows are
// handed to the threads one at a time. The quantisation needs each
// coefficient's range over the whole image before any byte can be written, so the fit makes
// TWO passes: pass 1 fits every pixel and keeps the per-row minima and maxima; pass 2 fits
// every pixel again, rounds the coefficients to float and quantises them, and measures the fit
// error, which needs the samples: the bands are read again unless the whole stack was one
// band. Floats, not doubles, because RtiFit version 2 kept the coefficients between the passes
// as floats and the bytes stay those: the quantisation step is at least 1/255 of the range,
// and rounding to float moves a coefficient by at most 2^-24 of its value, which moves about
// one byte in a million by one level.
// Why fit twice rather than keep the coefficients (6 floats a pixel for LRGB, 3*T for RGB PTM
// and HSH: 648 MB for HSH of 36 x 3000x2000): the memory holding them had to be faulted in
// page by page, which on the 2-core virtual machines Surrogate is measured on cost more than
// fitting again (docs/developer-guide.md, "Benchmarks"), and it raised the peak by as much.
// Small sets of coefficients are kept (at most 128 MiB, within the budget beside the band):
// pass 2 then takes pass 1's floats instead of fitting again, the same bytes. At 36 x 1200x800
// (23 MB for LRGB, 104 MB for HSH order 2) RtiFit took 0.180 -> 0.139 s and 0.169 -> 0.152 s
// with far lights, 0.426 -> 0.386 s and 0.440 -> 0.346 s with near ones (medians of 7 and 5
// alternating runs, 2 threads).
// O(height * N) statistics come on top of the budget.
//
// Determinism: every pixel is computed by the same sequence of floating-point operations
// whatever the band height or thread count; reductions are kept per row and combined in row
// order, so results (bytes and statistics) are bit-identical for any threads/budget.
//
// Lights at known positions (FitOptions::nearLights, fit/near_lights.h; docs/hrti-math.md, "Near
// lights in the fit"): each pixel p has its own light matrix, from the directions
// l_i(p) = normalize(X_i - p), and its samples are multiplied by the fall-off factors
// f_i(p) = |X_i - p|^2 / r_i^2 before fitting, so a pixel's coefficients are the least-squares
// fit (same basis, same conditioning rule) to its own normalised samples, and relighting the
// file from one direction shows the surface under a distant light from there. The exact
// inverse P(p) is computed at nodes every G pixels (G = d / 48 from the lights' closest
// approach d to the frame, 2..64) and interpolated bilinearly; its error against the exact
// per-pixel inverse moves no normal by 0.01 degree (tests/fit/test_near_lights.cpp); the f_i
// are exact per pixel. The conditioning weight is one for the frame: the largest any node's
// own light matrix asks for. The fit's statistics then re-render the stored model at each
// pixel's own direction, divide by f_i and compare with the photograph: PSNR "relit at the
// captured lights". The passes, bands and determinism are those below; every value is a
// function of (x, y) alone. When no light is near, the fit is the far fit, byte for byte.
//
//   FitOptions options;
//   options.basis = Basis::PtmLrgb;
//   FitStatistics stats;
//   formats::PtmFile ptm = fitPtm(stack, lights, options, &stats);
//   formats::writePtm("object.ptm", ptm);
//   log(stats.psnr);
#pragma once

#include <array>
#include <cstddef>
#include <functional>
#include <string>
#include <utility>
#include <vector>

#include "core/stack.h"
#include "fit/basis.h"
#include "fit/near_lights.h"
#include "formats/ptm.h"
#include "formats/rti_hsh.h"

namespace surrogate::fit {

using Parameters = std::vector<std::pair<std::string, std::string>>;

// How a fit measures its errors (FitStatistics), chosen by the RtiFit step's version:
//   Serial  RtiFit version 7 and earlier, whose records still re-execute that way: in double
//           precision, each light's squared errors added one pixel after the other;
//   Lanes   version 8 on: the squares added in eight interleaved partial sums, which the
//           processor adds side by side, combined pairwise. Lights at infinity also compare in
//           single precision (fit/error_kernels.h says exactly how, and why); lights at known
//           positions stay in double precision, the lanes over each block of their pixels
//           (fit/near_fit.h).
// The model files are the same either way.
enum class ErrorMeasure { Serial, Lanes };

struct FitOptions {
  // Recorded in the carrier (they change the result):
  Basis basis = Basis::PtmLrgb;  // which model and which file (.ptm or .rti)
  // Lights at known positions (fit/near_lights.h): empty, or one entry per light. Empty, or no
  // entry near, is every light at infinity: today's fit, the same bytes. Not in toParameters():
  // the stage records the positions itself.
  std::vector<NearLight> nearLights;

  // How the statistics are measured (above): chosen by the RtiFit step's version, never a
  // parameter.
  ErrorMeasure errors = ErrorMeasure::Lanes;

  // Not recorded (the result is bit-identical whatever their value):
  std::size_t memoryBudgetBytes = 2ull << 30;  // the output model plus the row bands; smaller = thinner bands
  int threads = 0;                             // 0 = all cores
  std::function<void(double fraction)> progress;  // called from the calling thread, 0..1

  // Name/value pairs for the carrier's step parameters: {"basis", "ptm-lrgb"}.
  Parameters toParameters() const;
  // The inverse; missing names keep their defaults. Throws Error(Input) for an unknown name or
  // value (a carrier written by a newer version, or edited by hand).
  static FitOptions fromParameters(const Parameters& parameters);
};

// How well the QUANTISED model reproduces the photographs: each photograph is re-rendered at
// its own light from the stored bytes (clamped to 0..255, not rounded) and compared with the
// captured image, on Rec. 709 luminance in 0..255 units, over every pixel. With near lights
// (FitOptions::nearLights), "its own light" is each pixel's own direction to the light, and the
// rendering is divided by the pixel's fall-off factor before the clamp: the PSNR is that of the
// model relit at the captured lights. The conditioning figures are then the worst node's, the
// rank the lowest (docs/hrti-math.md, "Near lights in the fit").
struct FitStatistics {
  double rmse = 0;                  // over all pixels of all photographs
  double psnr = 0;                  // 20 log10(255 / rmse), capped at 100 dB (rmse ~ 0)
  std::vector<double> perImageRmse; // one per photograph, in stack order
  int rank = 0;                     // rank of the light matrix; < terms = degenerate lights
  int passes = 0;                   // times the stack was read (1 or 2); not a result
  // The light set's conditioning (docs/hrti-math.md, "Conditioning on the light set"):
  double conditionNumber = 0;       // largest / smallest singular value of the light matrix
                                    // (infinity when rank deficient)
  double noiseGain = 0;             // quantisation noise gain at the captured lights, as fitted
  double plainNoiseGain = 0;        // the same for plain least squares
  double regularisation = 0;        // weight mu on the damped terms; exactly 0 for plain least squares
  std::vector<int> dampedTerms;     // coefficient indices damped toward the lower order (empty when mu = 0)
  double lightSpreadDegrees = 0;    // largest angle between a light and the view axis
};

// A sentence for the log when `stats` says the fit was conditioned, "" otherwise: "the 12 lights
// lie within 25 degrees of the view axis: HSH order 3's five highest terms were damped toward
// order 2 (weight 1, noise gain 1818 -> 28.7); its PSNR is 35.20 dB".
std::string conditioningWarning(Basis basis, int lights, const FitStatistics& stats);

// Fits a .ptm (options.basis PtmLrgb or PtmRgb). `lights` are the N light directions in
// stack order (x right, y up, z towards the camera; normalised here). Throws Error(Input)
// when the light count differs from the stack's, a light is not a direction, there are fewer
// photographs than terms, or the stack is empty; Error(Usage) for an HSH basis.
formats::PtmFile fitPtm(const ImageStack& stack, const std::vector<std::array<double, 3>>& lights,
                        const FitOptions& options, FitStatistics* stats = nullptr);

// Fits an .rti HSH file (options.basis Hsh2 or Hsh3), same rules.
formats::HshFile fitHsh(const ImageStack& stack, const std::vector<std::array<double, 3>>& lights,
                        const FitOptions& options, FitStatistics* stats = nullptr);

}  // namespace surrogate::fit
