#include "fit/stream_fit.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include "core/error.h"
#include "core/parallel.h"
#include "core/resident.h"

namespace surrogate::fit {

namespace {
const char* const kStep = "fit";
constexpr std::size_t kBandBytes = std::size_t(8) << 20;  // see streamFit
constexpr int kHeldBands = 32;  // bands of a pass over images held in memory (see streamFit)
// The most coefficients kept between the passes instead of fitting every row twice (fit.h).
constexpr std::size_t kMaxKeptBytes = std::size_t(128) << 20;
}  // namespace

std::vector<std::array<double, 3>> checkedLights(const ImageStack& stack,
                                                 const std::vector<std::array<double, 3>>& lights,
                                                 Basis basis) {
  const int terms = basisTerms(basis);
  if (stack.size() == 0 || stack.width() <= 0 || stack.height() <= 0) {
    throw Error(ErrorKind::Input, "", kStep, "there are no photographs to fit");
  }
  if (stack.channels() != 1 && stack.channels() != 3) {
    throw Error(ErrorKind::Input, "", kStep, "the photographs must be RGB or grey images");
  }
  if (static_cast<int>(lights.size()) != stack.size()) {
    throw Error(ErrorKind::Input, "", kStep,
                "there are " + std::to_string(stack.size()) + " photographs but " +
                    std::to_string(lights.size()) + " light directions; they must pair up");
  }
  if (stack.size() < terms) {
    throw Error(ErrorKind::Input, "", kStep,
                std::string("the basis ") + basisName(basis) + " fits " + std::to_string(terms) +
                    " coefficients per pixel and needs at least " + std::to_string(terms) +
                    " photographs; there are " + std::to_string(stack.size()));
  }
  std::vector<std::array<double, 3>> out;
  for (std::size_t i = 0; i < lights.size(); ++i) {
    const auto& l = lights[i];
    const double n = std::sqrt(l[0] * l[0] + l[1] * l[1] + l[2] * l[2]);
    if (!std::isfinite(n) || n < 1e-4) {
      throw Error(ErrorKind::Input, "", kStep,
                  "light " + std::to_string(i + 1) + " is not a direction (zero or invalid)");
    }
    out.push_back({l[0] / n, l[1] / n, l[2] / n});
  }
  return out;
}

std::vector<double> streamFit(const ImageStack& stack, RowFitter& fitter,
                              const FitOptions& options, std::size_t modelBytes, int* passes) {
  const int n = stack.size(), w = stack.width(), h = stack.height(), ch = stack.channels();
  const int threads = effectiveThreads(options.threads);
  const std::size_t rowSamples = static_cast<std::size_t>(w) * 3;
  const std::size_t bandRowBytes = static_cast<std::size_t>(n) * rowSamples * 2;
  const std::size_t scratchBytes =
      static_cast<std::size_t>(threads) * (fitter.scratchDoubles(w) * sizeof(double) +
                                           (ch == 1 ? rowSamples * 2 : 0));
  const std::size_t fixedBytes = scratchBytes + modelBytes;
  const std::size_t available =
      options.memoryBudgetBytes > fixedBytes ? options.memoryBudgetBytes - fixedBytes : 0;
  // Bands of at most kBandBytes even when the budget would hold the whole stack: a band is
  // written once and read a few times while it is hot, and pages of a buffer the size of the
  // stack cost more to fault in than reading the stack twice (the decoded stack is in memory
  // when it fits the budget, or read back sequentially from its file when it does not). 8 MiB
  // rather than 32: as fast (36 x 3000x2000, 1200x800, every basis, three paired runs) and
  // 24 MiB less at the peak.
  const std::size_t bandBytes = std::min(available, kBandBytes);
  // RGB images already in memory (the decoded stacks when they fit --memory) are read where
  // they are: no band buffer, no copy, and 8-bit sources stay bytes (ImageStack::heldByteRow).
  const bool heldBytes = ch == 3 && stack.heldByteRow(0, 0) != nullptr;
  const bool held = heldBytes || (ch == 3 && stack.heldRow(0, 0) != nullptr);
  int band = static_cast<int>(std::clamp<std::size_t>(bandBytes / bandRowBytes, 1, static_cast<std::size_t>(h)));
  // Held images need no buffer, so their bands are only the steps of the progress bar: each
  // band ends with the workers waiting for the slowest row, and bands of a buffer's height
  // (12 rows of 36 x 3000x2000) made 167 such waits a pass.
  if (held) band = std::max(band, (h + kHeldBands - 1) / kHeldBands);
  const int bands = (h + band - 1) / band;
  std::vector<std::uint16_t> buffer(held ? 0 : static_cast<std::size_t>(n) * band * rowSamples);
  // The coefficients kept between the passes, when the fitter can and they are small enough
  // (kMaxKeptBytes) to fit beside the band within the budget.
  const std::size_t keptBytes = static_cast<std::size_t>(h) * fitter.keptPerRow(w) * sizeof(float);
  std::vector<float> kept;
  if (keptBytes > 0 && keptBytes <= kMaxKeptBytes && keptBytes + bandBytes <= available) {
    // Backed on all the fit's threads at once (core/resident.h): where the block is fresh
    // memory (hsh2 after ptm-lrgb at 36 x 1200x800: 34 of its 46 MB) that was 30-70 ms of
    // one core clearing pages, the other idle.
    resizeResident(kept, keptBytes / sizeof(float), threads);
    fitter.keep(kept.data());
  }

  auto readBand = [&](int y0, int y1) {
    if (held) return;
    parallelFor(static_cast<std::size_t>(n), 1, threads, [&](std::size_t b, std::size_t e) {
      std::vector<std::uint16_t> grey;
      for (std::size_t i = b; i < e; ++i) {
        std::uint16_t* dst = buffer.data() + i * band * rowSamples;
        if (ch == 3) {
          stack.readRows(static_cast<int>(i), y0, y1, dst);
        } else {  // grey: R = G = B
          grey.resize(static_cast<std::size_t>(y1 - y0) * w);
          stack.readRows(static_cast<int>(i), y0, y1, grey.data());
          for (std::size_t p = 0; p < grey.size(); ++p)
            dst[3 * p] = dst[3 * p + 1] = dst[3 * p + 2] = grey[p];
        }
      }
    });
  };
  // Each worker's scratch, allocated (zeroed) at its first row of a pass and handed to its
  // later rows: hundreds of kilobytes, which allocated and zeroed for every row cost 2 % of a fit.
  std::vector<std::vector<double>> scratches(static_cast<std::size_t>(threads));
  auto startPass = [&] {
    for (auto& s : scratches) std::vector<double>().swap(s);
  };
  // Runs fn(row, scratch) for rows [y0, y1) of the band in memory, on the workers.
  auto forRows = [&](int y0, int y1, const std::function<void(const RowView&, double*)>& fn) {
    const std::size_t rows = static_cast<std::size_t>(y1 - y0);
    // Rows one at a time: a row is a millisecond or more of work against one atomic increment,
    // and the band's end waits at most one row for the slowest worker.
    parallelForWorkers(rows, 1, threads, [&](int worker, std::size_t b, std::size_t e) {
      std::vector<double>& scratch = scratches[static_cast<std::size_t>(worker)];
      if (scratch.empty()) scratch.resize(fitter.scratchDoubles(w));
      std::vector<const std::uint16_t*> images(n);
      std::vector<const std::uint8_t*> bytes(n);
      for (std::size_t r = b; r < e; ++r) {
        const int y = y0 + static_cast<int>(r);
        for (int i = 0; i < n; ++i) {
          if (heldBytes) bytes[i] = stack.heldByteRow(i, y);
          else if (held) images[i] = stack.heldRow(i, y);
          else images[i] = buffer.data() + (static_cast<std::size_t>(i) * band + r) * rowSamples;
          if (heldBytes ? !bytes[i] : !images[i])
            throw Error(ErrorKind::Internal, "", kStep, "a photograph's row is not held where the others are");
        }
        fn(RowView{heldBytes ? nullptr : images.data(), heldBytes ? bytes.data() : nullptr, w, y}, scratch.data());
      }
    });
  };
  auto report = [&](double fraction) {
    if (options.progress) options.progress(fraction);
  };

  // Pass 1: ranges, kept per row and combined afterwards (min/max are exact in any order).
  const int r = fitter.ranges();
  std::vector<double> rowLo(static_cast<std::size_t>(h) * r), rowHi(rowLo.size());
  startPass();
  for (int bi = 0; bi < bands; ++bi) {
    const int y0 = bi * band, y1 = std::min(h, y0 + band);
    readBand(y0, y1);
    forRows(y0, y1, [&](const RowView& row, double* scratch) {
      fitter.measure(row, scratch, &rowLo[static_cast<std::size_t>(row.y) * r],
                     &rowHi[static_cast<std::size_t>(row.y) * r]);
    });
    report(0.5 * (bi + 1) / bands);
  }
  std::vector<double> lo(r, std::numeric_limits<double>::infinity());
  std::vector<double> hi(r, -std::numeric_limits<double>::infinity());
  for (int y = 0; y < h; ++y) {
    for (int k = 0; k < r; ++k) {
      lo[k] = std::min(lo[k], rowLo[static_cast<std::size_t>(y) * r + k]);
      hi[k] = std::max(hi[k], rowHi[static_cast<std::size_t>(y) * r + k]);
    }
  }
  fitter.setRanges(lo, hi);

  // Pass 2: quantise and measure; a single band is still in memory and is not read again.
  std::vector<double> rowErr(static_cast<std::size_t>(h) * n);
  startPass();
  for (int bi = 0; bi < bands; ++bi) {
    const int y0 = bi * band, y1 = std::min(h, y0 + band);
    if (bands > 1) readBand(y0, y1);
    forRows(y0, y1, [&](const RowView& row, double* scratch) {
      fitter.quantise(row, scratch, &rowErr[static_cast<std::size_t>(row.y) * n]);
    });
    report(0.5 + 0.5 * (bi + 1) / bands);
  }
  fitter.keep(nullptr);
  if (passes) *passes = bands > 1 ? 2 : 1;
  std::vector<double> sqErr(n, 0.0);
  for (int y = 0; y < h; ++y)
    for (int i = 0; i < n; ++i) sqErr[i] += rowErr[static_cast<std::size_t>(y) * n + i];
  return sqErr;
}

void finishStatistics(const std::vector<double>& sqErr, std::size_t pixels, int rank, int passes,
                      FitStatistics* stats) {
  if (!stats) return;
  stats->perImageRmse.clear();
  double total = 0;
  for (double e : sqErr) {
    stats->perImageRmse.push_back(std::sqrt(e / static_cast<double>(pixels)));
    total += e;
  }
  stats->rmse = std::sqrt(total / (static_cast<double>(pixels) * sqErr.size()));
  stats->psnr = 20.0 * std::log10(255.0 / std::max(stats->rmse, 255e-5));
  stats->rank = rank;
  stats->passes = passes;
}

}  // namespace surrogate::fit
