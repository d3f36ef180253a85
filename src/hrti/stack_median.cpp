#include "hrti/stack_median.h"

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <memory>
#include <new>
#include <string>
#include <utility>

#if defined(__x86_64__) && defined(__GNUC__)
#include <immintrin.h>
#endif

#include "core/cpu_features.h"
#include "core/error.h"
#include "core/parallel.h"
#include "core/resident.h"
#include "hrti/merge_exchange.h"

namespace surrogate::hrti {

namespace {

constexpr const char* kStep = "median";
// Full-resolution rows one thread reads at once when reducing an image that is not in memory.
constexpr std::size_t kReadBytes = std::size_t(1) << 20;

// The sample of rank `rank` (0: the smallest); reorders them.
std::uint16_t ranked(std::vector<std::uint16_t>& samples, int rank) {
  const auto at = samples.begin() + rank;
  std::nth_element(samples.begin(), at, samples.end());
  return *at;
}

// The ranks wanted of each pixel's samples, each with where its values go (out[p] for pixel p).
using Ranks = std::vector<std::pair<int, std::uint16_t*>>;

#if defined(__x86_64__) && defined(__GNUC__)
// The samples of each rank of `ranks` of pixels [b, e) sixteen at a time (the 16-bit samples of one
// pixel in one lane of n registers, sorted by `sort`); returns the first pixel left for the
// caller. The sort is exact, so this gives what nth_element gives; in a `perf` profile of `surrogate
// lights` on 36 x 3000x2000 the medians went from 4.3 to 0.5 % of the samples.
__attribute__((target("avx2"))) std::size_t rankedAvx2(const std::uint16_t* planes, int n, const Ranks& ranks,
                                                       std::size_t plane, std::size_t b, std::size_t e,
                                                       const CompareExchanges& sort) {
  // The n registers' worth in memory of their alignment (a std::vector drops it).
  const std::unique_ptr<void, void (*)(void*)> block(std::aligned_alloc(32, sizeof(__m256i) * n), std::free);
  if (!block) throw std::bad_alloc();
  __m256i* v = static_cast<__m256i*>(block.get());
  std::size_t p = b;
  for (; p + 16 <= e; p += 16) {
    for (int i = 0; i < n; ++i)
      v[i] = _mm256_loadu_si256(reinterpret_cast<const __m256i*>(planes + i * plane + p));
    for (const auto& [i, j] : sort) {
      const __m256i low = _mm256_min_epu16(v[i], v[j]);
      v[j] = _mm256_max_epu16(v[i], v[j]);
      v[i] = low;
    }
    for (const auto& [rank, out] : ranks) _mm256_storeu_si256(reinterpret_cast<__m256i*>(out + p), v[rank]);
  }
  return p;
}
#endif

// out[p] = the sample of rank `rank` of planes[i * plane + p] over the n planes, for every
// p < plane and every (rank, out) of `ranks`.
void rankedOfPlanes(const std::uint16_t* planes, int n, const Ranks& ranks, std::size_t plane, int threads) {
#if defined(__x86_64__) && defined(__GNUC__)
  const bool avx2 = cpuHasAvx2() && n > 1;
#else
  const bool avx2 = false;
#endif
  const CompareExchanges sort = avx2 ? mergeExchangeSort(n) : CompareExchanges();
  parallelFor(plane, 4096, effectiveThreads(threads), [&](std::size_t b, std::size_t e) {
    std::size_t p = b;
#if defined(__x86_64__) && defined(__GNUC__)
    if (avx2) p = rankedAvx2(planes, n, ranks, plane, b, e, sort);
#endif
    std::vector<std::uint16_t> samples(n);
    for (; p < e; ++p) {
      for (int i = 0; i < n; ++i) samples[i] = planes[i * plane + p];
      // nth_element only reorders: the next rank is found as exactly among the reordered samples.
      for (const auto& [rank, out] : ranks) out[p] = ranked(samples, rank);
    }
  });
}

const ImageStack& checked(const ImageStack* stack) {
  if (!stack || stack->channels() != 1 || stack->size() == 0 || stack->width() == 0 || stack->height() == 0)
    throw Error(ErrorKind::Internal, "", kStep, "the median needs a non-empty one-channel stack");
  return *stack;
}

// The rounded means of `blocks` whole F x F blocks from their column sums: the count known to
// the compiler, the division is a multiplication (a 64-bit division by a count known only at
// run time took half of the reduction's time). 32-bit sums: F * F * 65535 + F * F / 2 < 2^32.
template <int F>
int wholeBlockMeans(const std::uint32_t* columns, int blocks, std::uint16_t* out) {
  static_assert(F <= 16, "a block's sum must stay within 32 bits");
  constexpr std::uint32_t kCount = F * F;
  for (int b = 0; b < blocks; ++b) {
    std::uint32_t sum = 0;
    for (int j = 0; j < F; ++j) sum += columns[b * F + j];
    out[b] = static_cast<std::uint16_t>((sum + kCount / 2) / kCount);
  }
  return blocks;
}

// wholeBlockMeans for the usual factors (a frame up to 16 times the coarse width); 0 blocks done
// for the others.
int wholeBlockMeans(const std::uint32_t* columns, int factor, int blocks, std::uint16_t* out) {
  switch (factor) {
    case 2: return wholeBlockMeans<2>(columns, blocks, out);
    case 3: return wholeBlockMeans<3>(columns, blocks, out);
    case 4: return wholeBlockMeans<4>(columns, blocks, out);
    case 5: return wholeBlockMeans<5>(columns, blocks, out);
    case 6: return wholeBlockMeans<6>(columns, blocks, out);
    case 7: return wholeBlockMeans<7>(columns, blocks, out);
    case 8: return wholeBlockMeans<8>(columns, blocks, out);
    case 9: return wholeBlockMeans<9>(columns, blocks, out);
    case 10: return wholeBlockMeans<10>(columns, blocks, out);
    case 11: return wholeBlockMeans<11>(columns, blocks, out);
    case 12: return wholeBlockMeans<12>(columns, blocks, out);
    case 13: return wholeBlockMeans<13>(columns, blocks, out);
    case 14: return wholeBlockMeans<14>(columns, blocks, out);
    case 15: return wholeBlockMeans<15>(columns, blocks, out);
    case 16: return wholeBlockMeans<16>(columns, blocks, out);
    default: return 0;
  }
}

// The block means of full-resolution rows [y0, y1) (whole blocks of `factor` rows, the last
// one possibly partial) as coarse rows: each the rounded mean of its block's pixels. The
// block's rows are added column by column first (a loop the compiler vectorises), then each
// block's columns: integer sums, the same in any order.
void reduceRows(const std::uint16_t* rows, int y0, int y1, int width, int factor, std::uint16_t* out) {
  const int coarseWidth = (width + factor - 1) / factor;
  std::vector<std::uint32_t> columns(width);  // at most kMaxFactor * 65535 each
  for (int by = y0; by < y1; by += factor) {
    const int blockRows = std::min(factor, y1 - by);
    std::fill(columns.begin(), columns.end(), 0);
    for (int y = by; y < by + blockRows; ++y) {
      const std::uint16_t* row = rows + std::size_t(y - y0) * width;
      for (int x = 0; x < width; ++x) columns[x] += row[x];
    }
    const int whole = blockRows == factor ? wholeBlockMeans(columns.data(), factor, width / factor, out) : 0;
    out += whole;
    for (int cx = whole; cx < coarseWidth; ++cx) {
      const int x0 = cx * factor, x1 = std::min(width, x0 + factor);
      std::uint64_t sum = 0;
      for (int x = x0; x < x1; ++x) sum += columns[x];
      const std::uint64_t count = std::uint64_t(blockRows) * (x1 - x0);
      *out++ = static_cast<std::uint16_t>((sum + count / 2) / count);
    }
  }
}

}  // namespace

int StackMedian::factorFor(int width, int coarseWidth) {
  if (coarseWidth <= 0) throw Error(ErrorKind::Internal, "", kStep, "the coarse width must be above 0");
  return static_cast<int>(std::clamp<long>(std::lround(double(width) / coarseWidth), 1, kMaxFactor));
}

StackMedian::StackMedian(std::shared_ptr<const ImageStack> luminance, int coarseWidth, int threads,
                         std::size_t coarseBudget, double quantile)
    : StackMedian(luminance, luminance.get(), coarseWidth, threads, quantile) {
  computeCoarse({this}, coarseBudget);
}

StackMedian::StackMedian(const ImageStack& luminance, int coarseWidth, int threads, std::size_t coarseBudget,
                         double quantile)
    : StackMedian(nullptr, &luminance, coarseWidth, threads, quantile) {
  computeCoarse({this}, coarseBudget);
}

std::pair<std::shared_ptr<StackMedian>, std::shared_ptr<StackMedian>> StackMedian::medianAnd(
    std::shared_ptr<const ImageStack> luminance, double other, int coarseWidth, int threads, std::size_t coarseBudget) {
  // Not make_shared: the constructor that leaves the coarse image to computeCoarse is private.
  std::shared_ptr<StackMedian> median(new StackMedian(luminance, luminance.get(), coarseWidth, threads, 0.5));
  std::shared_ptr<StackMedian> quantile(new StackMedian(luminance, luminance.get(), coarseWidth, threads, other));
  computeCoarse({median.get(), quantile.get()}, coarseBudget);
  return {median, quantile};
}

int StackMedian::rankFor(int n, double quantile) {
  if (!(quantile >= 0 && quantile <= 1))
    throw Error(ErrorKind::Internal, "", kStep, "a quantile of a stack must lie between 0 and 1");
  return std::clamp(static_cast<int>(std::floor(quantile * (n - 1))), 0, std::max(0, n - 1));
}

StackMedian::StackMedian(std::shared_ptr<const ImageStack> owner, const ImageStack* luminance, int coarseWidth,
                         int threads, double quantile)
    : owner_(std::move(owner)),
      stack_(checked(luminance)),
      threads_(threads),
      rank_(rankFor(stack_.size(), quantile)),
      factor_(factorFor(stack_.width(), coarseWidth)),
      tilesX_((stack_.width() + kTile - 1) / kTile),
      tilesY_((stack_.height() + kTile - 1) / kTile),
      tiles_(std::size_t(tilesX_) * tilesY_) {}

// Bands of coarse rows: every image's reduced band (each image reduced by one thread, into its
// own plane), then each median's rank of each coarse pixel over the planes.
void StackMedian::computeCoarse(const std::vector<StackMedian*>& medians, std::size_t coarseBudget) {
  const StackMedian& first = *medians.front();
  const ImageStack& stack = first.stack_;
  const int n = stack.size(), w = first.width(), h = first.height(), f = first.factor_, threads = first.threads_;
  const int cw = (w + f - 1) / f, ch = (h + f - 1) / f;
  for (StackMedian* m : medians) {
    if (&m->stack_ != &stack || m->factor_ != f || m->threads_ != threads)
      throw Error(ErrorKind::Internal, "", kStep, "medians computed together must share their stack and reduction");
    m->coarse_ = Image(cw, ch, 1);
    m->coarse_.transfer = first.transfer();
  }
  // A stack already in memory is read where it is: a copy of its rows would cost time for nothing.
  const auto* held = dynamic_cast<const MemoryImageStack*>(&stack);
  const std::size_t perCoarseRow = std::size_t(n) * cw * sizeof(std::uint16_t);
  const int bandRows = static_cast<int>(std::clamp<std::size_t>(coarseBudget / perCoarseRow, 1, std::size_t(ch)));
  const int rowsPerRead = static_cast<int>(std::max<std::size_t>(1, kReadBytes / (std::size_t(f) * w * 2)));
  std::vector<std::uint16_t> reduced;
  resizeResident(reduced, std::size_t(n) * bandRows * cw);
  std::vector<std::uint64_t> sums(n, 0);  // integer sums: the same in any order
  // Each worker's buffer of rows read at once, kept from band to band rather than made (and
  // cleared) afresh for every image of every band.
  const int workers = std::max(1, effectiveThreads(threads));
  std::vector<std::vector<std::uint16_t>> workerRows(held ? 0 : workers);
  const std::size_t rowsSize = std::size_t(std::min(rowsPerRead, bandRows)) * f * w;
  for (int cy0 = 0; cy0 < ch; cy0 += bandRows) {
    const int count = std::min(bandRows, ch - cy0);
    const std::size_t plane = std::size_t(count) * cw;
    parallelForWorkers(n, 1, workers, [&](int worker, std::size_t b, std::size_t e) {
      std::vector<std::uint16_t> none;
      std::vector<std::uint16_t>& rows = held ? none : workerRows[worker];
      if (!held && rows.size() < rowsSize) rows.resize(rowsSize);
      for (std::size_t i = b; i < e; ++i) {
        std::uint16_t* out = &reduced[i * plane];
        for (int cy = cy0; cy < cy0 + count; cy += rowsPerRead) {
          const int y0 = cy * f, y1 = std::min(h, std::min(cy + rowsPerRead, cy0 + count) * f);
          const std::uint16_t* from = rows.data();
          if (held)
            from = held->image(static_cast<int>(i)).pixels.data() + std::size_t(y0) * w;
          else
            stack.readRows(static_cast<int>(i), y0, y1, rows.data());
          reduceRows(from, y0, y1, w, f, out + std::size_t(cy - cy0) * cw);
        }
        for (std::size_t p = 0; p < plane; ++p) sums[i] += out[p];
      }
    });
    Ranks ranks;
    for (StackMedian* m : medians) ranks.emplace_back(m->rank_, &m->coarse_.pixels[std::size_t(cy0) * cw]);
    rankedOfPlanes(reduced.data(), n, ranks, plane, threads);
  }
  for (StackMedian* m : medians) {
    m->imageMeans_.resize(n);
    for (int i = 0; i < n; ++i) m->imageMeans_[i] = double(sums[i]) / (double(cw) * ch) / 65535.0;
  }
}

// Tiles firstTile..lastTile of one tile row: the tiles' window of every image (readWindow),
// then each pixel's median.
void StackMedian::computeTiles(int tileRow, int firstTile, int lastTile, int threads) const {
  const int n = stack_.size(), w = width();
  const int y0 = tileRow * kTile, y1 = std::min(height(), y0 + kTile), rows = y1 - y0;
  const int x0 = firstTile * kTile, x1 = std::min(w, (lastTile + 1) * kTile), span = x1 - x0;
  const std::size_t plane = std::size_t(rows) * span;
  std::vector<std::uint16_t> band(std::size_t(n) * plane);
  parallelFor(n, 1, effectiveThreads(threads), [&](std::size_t b, std::size_t e) {
    for (std::size_t i = b; i < e; ++i) stack_.readWindow(static_cast<int>(i), x0, y0, x1, y1, &band[i * plane]);
  });
  std::vector<std::uint16_t> medians(plane);
  rankedOfPlanes(band.data(), n, {{rank_, medians.data()}}, plane, threads);
  for (int tx = firstTile; tx <= lastTile; ++tx) {
    std::vector<std::uint16_t>& tile = tiles_[std::size_t(tileRow) * tilesX_ + tx];
    if (!tile.empty()) continue;
    const int tx0 = tx * kTile, tw = std::min(w, tx0 + kTile) - tx0;
    tile.resize(std::size_t(tw) * rows);
    for (int y = 0; y < rows; ++y)
      std::copy_n(&medians[std::size_t(y) * span + (tx0 - x0)], tw, &tile[std::size_t(y) * tw]);
  }
}

Image StackMedian::window(const Rect& r) const {
  if (r.w <= 0 || r.h <= 0 || r.x < 0 || r.y < 0 || r.x + r.w > width() || r.y + r.h > height())
    throw Error(ErrorKind::Internal, "", kStep,
                "a median window (" + std::to_string(r.x) + ", " + std::to_string(r.y) + ", " + std::to_string(r.w) +
                    " x " + std::to_string(r.h) + ") outside the " + std::to_string(width()) + "x" +
                    std::to_string(height()) + " frame");
  const int tx0 = r.x / kTile, tx1 = (r.x + r.w - 1) / kTile;
  const int ty0 = r.y / kTile, ty1 = (r.y + r.h - 1) / kTile;
  Image out(r.w, r.h, 1);
  out.transfer = transfer();
  std::lock_guard<std::mutex> lock(mutex_);
  for (int ty = ty0; ty <= ty1; ++ty) {
    int first = tx1 + 1, last = tx0 - 1;  // the tiles of this row not computed yet
    for (int tx = tx0; tx <= tx1; ++tx)
      if (tiles_[std::size_t(ty) * tilesX_ + tx].empty()) {
        first = std::min(first, tx);
        last = tx;
      }
    if (first <= last) computeTiles(ty, first, last, threads_);
    for (int tx = tx0; tx <= tx1; ++tx) {
      const std::vector<std::uint16_t>& tile = tiles_[std::size_t(ty) * tilesX_ + tx];
      const int tileX = tx * kTile, tileY = ty * kTile, tw = std::min(width(), tileX + kTile) - tileX;
      const int xa = std::max(r.x, tileX), xb = std::min(r.x + r.w, tileX + tw);
      const int ya = std::max(r.y, tileY), yb = std::min(r.y + r.h, std::min(height(), tileY + kTile));
      for (int y = ya; y < yb; ++y)
        std::copy_n(&tile[std::size_t(y - tileY) * tw + (xa - tileX)], xb - xa,
                    &out.pixels[std::size_t(y - r.y) * r.w + (xa - r.x)]);
    }
  }
  return out;
}

void StackMedian::prepare(const std::vector<Rect>& rects) const {
  std::vector<char> wanted(tiles_.size(), 0);
  for (const Rect& r : rects) {
    const int x0 = std::max(0, r.x), y0 = std::max(0, r.y);
    const int x1 = std::min(width(), r.x + r.w), y1 = std::min(height(), r.y + r.h);
    if (x1 <= x0 || y1 <= y0) continue;
    for (int ty = y0 / kTile; ty <= (y1 - 1) / kTile; ++ty)
      for (int tx = x0 / kTile; tx <= (x1 - 1) / kTile; ++tx) wanted[std::size_t(ty) * tilesX_ + tx] = 1;
  }
  std::lock_guard<std::mutex> lock(mutex_);
  // Runs of at most kPrepareRun missing tiles of one row, each computed by one thread: every
  // tile's median is its pixels' alone, so which thread computes it changes nothing.
  constexpr int kPrepareRun = 4;
  struct Run {
    int row, first, last;
  };
  std::vector<Run> runs;
  for (int ty = 0; ty < tilesY_; ++ty) {
    for (int tx = 0; tx < tilesX_; ++tx) {
      const std::size_t k = std::size_t(ty) * tilesX_ + tx;
      if (!wanted[k] || !tiles_[k].empty()) continue;
      if (!runs.empty() && runs.back().row == ty && runs.back().last == tx - 1 &&
          runs.back().last - runs.back().first + 1 < kPrepareRun)
        runs.back().last = tx;
      else
        runs.push_back({ty, tx, tx});
    }
  }
  parallelFor(runs.size(), 1, effectiveThreads(threads_), [&](std::size_t b, std::size_t e) {
    for (std::size_t i = b; i < e; ++i) computeTiles(runs[i].row, runs[i].first, runs[i].last, 1);
  });
}

}  // namespace surrogate::hrti
