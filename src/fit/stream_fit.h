// Private to src/fit: the two-pass, band-streaming driver shared by the PTM and HSH fits
// (the plan is described in fit.h). A RowFitter does the per-row maths; the driver reads the
// bands, runs rows on the workers and keeps the per-row reductions in row order.
#pragma once

#include <array>
#include <cstdint>
#include <vector>

#include "core/stack.h"
#include "fit/fit.h"

namespace surrogate::fit {

// One image row of every photograph: width*3 interleaved RGB samples each (grey stacks are
// expanded to RGB by the driver), as 16-bit samples (images) or, when the stack holds 8-bit
// sources in memory, as the bytes themselves (bytes; b stands for the 16-bit value 257 b). One of
// the two is null. withSamples(row, f) calls f with whichever the row has.
struct RowView {
  const std::uint16_t* const* images;
  const std::uint8_t* const* bytes;
  int width;
  int y;
};

template <typename F>
decltype(auto) withSamples(const RowView& row, F&& f) {
  return row.bytes ? f(row.bytes) : f(row.images);
}

class RowFitter {
 public:
  virtual ~RowFitter() = default;
  virtual int ranges() const = 0;                            // coefficient ranges tracked
  virtual std::size_t scratchDoubles(int width) const = 0;   // per worker
  // Pass 1: fits the row; lo/hi (ranges() each) receive the row's minima and maxima.
  virtual void measure(const RowView& row, double* scratch, double* lo, double* hi) const = 0;
  // Between the passes: the whole image's ranges.
  virtual void setRanges(const std::vector<double>& lo, const std::vector<double>& hi) = 0;
  // Pass 2: fits the row again, rounds its coefficients to float and quantises them into the
  // result's row `row.y`, and writes sqErr[i] = sum over the row of the squared luminance
  // error at light i.
  virtual void quantise(const RowView& row, double* scratch, double* sqErr) const = 0;
  // Coefficients one row keeps between the passes (0: the fitter cannot keep them). Given
  // keep(rows), pass 1 stores each row's coefficients rounded to float at rows + y *
  // keptPerRow(width), and pass 2 takes them from there instead of fitting the row again: the
  // same floats, so the same bytes.
  virtual std::size_t keptPerRow(int /*width*/) const { return 0; }
  virtual void keep(float* /*rows*/) {}
};

// Validated light vectors, normalised, for a fit of `basis` (at least as many photographs as it
// has terms). Throws Error(Input) naming the basis (see fitPtm).
std::vector<std::array<double, 3>> checkedLights(const ImageStack& stack,
                                                 const std::vector<std::array<double, 3>>& lights,
                                                 Basis basis);

// Runs both passes; returns the per-image squared luminance errors (summed over pixels in row
// order) and sets stats->passes. `modelBytes`, the model already allocated for the output,
// counts against options.memoryBudgetBytes like the bands do.
std::vector<double> streamFit(const ImageStack& stack, RowFitter& fitter,
                              const FitOptions& options, std::size_t modelBytes, int* passes);

void finishStatistics(const std::vector<double>& sqErr, std::size_t pixels, int rank, int passes,
                      FitStatistics* stats);

// Rec. 709 luminance weights (core/image.h luminance() uses the same).
constexpr double kLumR = 0.2126, kLumG = 0.7152, kLumB = 0.0722;

}  // namespace surrogate::fit
