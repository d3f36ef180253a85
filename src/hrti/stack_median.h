// Per-pixel median of an image stack (docs/hrti-math.md, "Spheres in the stack's median and upper quartile"), at the
// two resolutions sphere detection needs and no more.
//
// Shadows and highlights move from image to image; the spheres do not. The median over the
// stack keeps the spheres and drops both. The sphere search (hrti/sphere_detection.h) looks at
// a reduced frame, and only the surroundings of a sphere are needed at full resolution, so a
// full-resolution median of the whole frame (most of the stage's time on a large capture) is
// never made:
//
//   coarse()      every image reduced `factor()` times (the mean of each factor x factor block;
//                 the blocks at the right and bottom edges may be partial), then the per-pixel
//                 median of those reduced images. Computed once, on construction, reading the
//                 stack in row bands: memory O(N * band * coarse width), at most coarseBudget
//                 bytes of reduced images.
//   window(rect)  the per-pixel median at full resolution over a rectangle, computed on demand
//                 in 64 x 64 tiles that are kept for later calls (the highlight overview crops
//                 the surroundings the sphere refinement has already computed).
//
// For an even count the median is the lower of the two middle values (no averaging: a window's
// value is one of the measured values, exactly reproducible). Results are identical at any
// thread count. Given a quantile q, the same is made of the sample of rank floor(q (n - 1))
// instead (0.5: the lower median); sphere detection's rim uses an upper quantile
// (hrti/sphere_detection.h).
//
//   StackMedian m(luminance, 800, threads);     // coarse() about 800 pixels wide
//   Image around = m.window({x, y, 300, 300});  // full-resolution median there
#pragma once

#include <cstddef>
#include <cstdint>
#include <memory>
#include <mutex>
#include <utility>
#include <vector>

#include "core/image.h"
#include "core/stack.h"
#include "hrti/sphere_detection.h"

namespace surrogate::hrti {

class StackMedian {
 public:
  static constexpr int kTile = 64;
  // Bands of a couple of megabytes: the reduced planes stay in the cache between reducing and
  // ranking, and the buffer is mostly memory the process already backs. At 16 MiB (one band for
  // 36 x 1200x800) backing it fresh took 2 to 63 ms on one thread while the other core idled.
  static constexpr std::size_t kCoarseBudget = std::size_t(2) << 20;

  static constexpr int kMaxFactor = 65536;  // keeps a block's column sums within 32 bits
  // The integer reduction that brings `width` nearest to `coarseWidth` pixels (at least 1, at
  // most kMaxFactor).
  static int factorFor(int width, int coarseWidth);

  // A one-channel, non-empty stack; kept (shared) for the full-resolution windows.
  StackMedian(std::shared_ptr<const ImageStack> luminance, int coarseWidth, int threads,
              std::size_t coarseBudget = kCoarseBudget, double quantile = 0.5);
  // The same over a stack the caller keeps alive as long as this median.
  StackMedian(const ImageStack& luminance, int coarseWidth, int threads, std::size_t coarseBudget = kCoarseBudget,
              double quantile = 0.5);
  // The rank (0: the smallest) of quantile q among n samples: floor(q (n - 1)).
  static int rankFor(int n, double quantile);

  // The median and the quantile `other` of one stack from a single reading of it: the same
  // coarse images and windows as two StackMedians made one after the other, for half the
  // reading and reducing (sphere detection needs both; the reading was a tenth of a run).
  static std::pair<std::shared_ptr<StackMedian>, std::shared_ptr<StackMedian>> medianAnd(
      std::shared_ptr<const ImageStack> luminance, double other, int coarseWidth, int threads,
      std::size_t coarseBudget = kCoarseBudget);

  int width() const { return stack_.width(); }  // full resolution
  int height() const { return stack_.height(); }
  Transfer transfer() const { return stack_.transfer(); }
  int factor() const { return factor_; }
  const ImageStack& stack() const { return stack_; }
  // Each image's mean value (0..1), from its reduced copy: what the exposure check compares.
  const std::vector<double>& imageMeans() const { return imageMeans_; }
  const Image& coarse() const { return coarse_; }  // ceil(width / factor) x ceil(height / factor)

  // The full-resolution median over `rect`, which must lie inside the frame. Safe to call
  // from several threads.
  Image window(const Rect& rect) const;
  // Computes now the tiles of every rect of `rects` (each clipped to the frame) not computed yet,
  // several tile rows at once: what window() would compute for them one call at a time, while
  // the callers of window() waited for its lock. Safe to call from several threads.
  void prepare(const std::vector<Rect>& rects) const;

 private:
  // `owner` keeps `luminance` alive, or is empty when the caller does.
  StackMedian(std::shared_ptr<const ImageStack> owner, const ImageStack* luminance, int coarseWidth, int threads,
              double quantile);
  // The coarse images of every median of `medians` (all of one stack, factor and thread count)
  // from one reading of the stack.
  static void computeCoarse(const std::vector<StackMedian*>& medians, std::size_t coarseBudget);
  // Tiles firstTile..lastTile of one tile row, read and ranked on `threads` threads; the caller
  // holds mutex_.
  void computeTiles(int tileRow, int firstTile, int lastTile, int threads) const;

  std::shared_ptr<const ImageStack> owner_;  // empty when the caller keeps the stack
  const ImageStack& stack_;
  int threads_;
  int rank_;
  int factor_;
  Image coarse_;
  std::vector<double> imageMeans_;
  int tilesX_, tilesY_;
  mutable std::mutex mutex_;
  mutable std::vector<std::vector<std::uint16_t>> tiles_;  // row-major tiles; empty: not yet computed
};

}  // namespace surrogate::hrti
