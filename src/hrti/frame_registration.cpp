#include "hrti/frame_registration.h"

#include <opencv2/core.hpp>
#include <opencv2/imgproc.hpp>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <memory>
#include <new>

#if defined(__x86_64__) && defined(__GNUC__)
#include <immintrin.h>
#endif

#include "core/cpu_features.h"
#include "core/parallel.h"
#include "hrti/merge_exchange.h"
#include "hrti/phase_correlation.h"

namespace surrogate::hrti {

namespace {

constexpr double kSmoothSigma = 1.0;  // reduced pixels

// Frame `index` reduced f times: the mean of the f pixels of each f x f block's middle row (the
// right and bottom remainders left out), 0..1. The f samples' sum is an integer, exact in double
// whatever the order: summed as integers first, the division vectorises.
cv::Mat reduced(const ImageStack& stack, int index, int f) {
  const int w = stack.width() / f, h = stack.height() / f;
  cv::Mat out(h, w, CV_32F);
  std::vector<std::uint16_t> row(static_cast<std::size_t>(stack.width()));
  std::vector<std::int32_t> sums(static_cast<std::size_t>(w));
  const double scale = 65535.0 * f;
  for (int y = 0; y < h; ++y) {
    stack.readWindow(index, 0, y * f + f / 2, w * f, y * f + f / 2 + 1, row.data());
    const std::uint16_t* in = row.data();
    if (f == 2) {
      for (int x = 0; x < w; ++x) sums[static_cast<std::size_t>(x)] = in[2 * x] + in[2 * x + 1];
    } else {
      for (int x = 0; x < w; ++x) {
        std::int32_t sum = 0;
        for (int k = 0; k < f; ++k) sum += in[static_cast<std::size_t>(x * f + k)];
        sums[static_cast<std::size_t>(x)] = sum;
      }
    }
    float* to = out.ptr<float>(y);
    for (int x = 0; x < w; ++x) to[x] = static_cast<float>(sums[static_cast<std::size_t>(x)] / scale);
  }
  return out;
}

// Rows [b, e) of the per-pixel median of `frames`, each pixel's value of rank `rank`, from column
// x0 on (columns before it done by the caller).
void medianRows(const std::vector<cv::Mat>& frames, int rank, std::size_t b, std::size_t e, int x0, cv::Mat& median) {
  std::vector<float> values(frames.size());
  for (std::size_t y = b; y < e; ++y) {
    float* out = median.ptr<float>(static_cast<int>(y));
    for (int x = x0; x < median.cols; ++x) {
      for (std::size_t i = 0; i < frames.size(); ++i) values[i] = frames[i].ptr<float>(static_cast<int>(y))[x];
      std::nth_element(values.begin(), values.begin() + rank, values.end());
      out[x] = values[static_cast<std::size_t>(rank)];
    }
  }
}

#if defined(__x86_64__) && defined(__GNUC__)
// As medianRows, eight pixels at a time (the values of one pixel in one lane of n registers,
// sorted by `sort`); returns the first column left for medianRows. Min and max only move values
// (and the reduced values are finite, never NaN), so this is the value nth_element picks. In a
// `perf` profile of `surrogate run` on 36 frames of 1200x800 the median went from 2.4 to 0.5 % of
// the samples.
__attribute__((target("avx2"))) int medianRowsAvx2(const std::vector<cv::Mat>& frames, int rank, std::size_t b,
                                                   std::size_t e, const CompareExchanges& sort, cv::Mat& median) {
  constexpr int kLanes = 8;
  const int n = static_cast<int>(frames.size()), cols = median.cols / kLanes * kLanes;
  // The n registers' worth in memory of their alignment (a std::vector drops it).
  const std::unique_ptr<void, void (*)(void*)> block(std::aligned_alloc(32, sizeof(__m256) * n), std::free);
  if (!block) throw std::bad_alloc();
  __m256* v = static_cast<__m256*>(block.get());
  for (std::size_t y = b; y < e; ++y) {
    float* out = median.ptr<float>(static_cast<int>(y));
    for (int x = 0; x < cols; x += kLanes) {
      for (int i = 0; i < n; ++i)
        v[i] = _mm256_loadu_ps(frames[static_cast<std::size_t>(i)].ptr<float>(static_cast<int>(y)) + x);
      for (const auto& [i, j] : sort) {
        const __m256 low = _mm256_min_ps(v[i], v[j]);
        v[j] = _mm256_max_ps(v[i], v[j]);
        v[i] = low;
      }
      _mm256_storeu_ps(out + x, v[rank]);
    }
  }
  return cols;
}
#endif

// The per-pixel median of the reduced frames (at least two, one size): the lower of the two
// middle values.
cv::Mat medianOf(const std::vector<cv::Mat>& frames, int workers) {
  const int n = static_cast<int>(frames.size()), rank = (n - 1) / 2;
  cv::Mat median(frames.front().rows, frames.front().cols, CV_32F);
#if defined(__x86_64__) && defined(__GNUC__)
  const bool avx2 = cpuHasAvx2();
#else
  const bool avx2 = false;
#endif
  // Only the compare-exchanges the middle value depends on.
  const CompareExchanges sort = avx2 ? neededFor(mergeExchangeSort(n), n, rank) : CompareExchanges();
  parallelFor(static_cast<std::size_t>(median.rows), 8, workers, [&](std::size_t b, std::size_t e) {
    int x0 = 0;
#if defined(__x86_64__) && defined(__GNUC__)
    if (avx2) x0 = medianRowsAvx2(frames, rank, b, e, sort, median);
#endif
    medianRows(frames, rank, b, e, x0, median);
  });
  return median;
}

// One thread's images of gradient(), reused from frame to frame (fresh ones each frame were
// fresh pages each time).
struct GradientBuffers {
  cv::Mat smooth, gx, gy, magnitude;
};

const cv::Mat& gradient(const cv::Mat& image, GradientBuffers& b) {
  // Smoothed first: at full resolution (f = 1) a noisy or strongly compressed frame's gradient is
  // mostly noise, which pulls the correlation peak (a clean 480 px frame measured 4 px).
  cv::GaussianBlur(image, b.smooth, cv::Size(0, 0), kSmoothSigma);
  cv::Sobel(b.smooth, b.gx, CV_32F, 1, 0);
  cv::Sobel(b.smooth, b.gy, CV_32F, 0, 1);
  cv::magnitude(b.gx, b.gy, b.magnitude);
  return b.magnitude;
}

struct Fit {
  bool ok = false;
  double tx = 0, ty = 0, theta = 0, worst = 1e300;
};

// The rigid motion s = t + theta (-cy, cx) through the shifts `used` of the quarters (centres c
// relative to the frame's centre), by least squares.
Fit fitMotion(const std::array<cv::Point2d, 4>& centre, const std::array<cv::Point2d, 4>& shift,
              const std::vector<int>& used) {
  cv::Mat a(static_cast<int>(used.size()) * 2, 3, CV_64F, cv::Scalar(0)), b(a.rows, 1, CV_64F);
  for (std::size_t k = 0; k < used.size(); ++k) {
    const int q = used[k], r = static_cast<int>(2 * k);
    a.at<double>(r, 0) = 1;
    a.at<double>(r, 2) = -centre[q].y;
    b.at<double>(r) = shift[q].x;
    a.at<double>(r + 1, 1) = 1;
    a.at<double>(r + 1, 2) = centre[q].x;
    b.at<double>(r + 1) = shift[q].y;
  }
  cv::Mat x;
  Fit f;
  if (!cv::solve(a, b, x, cv::DECOMP_SVD)) return f;
  f.tx = x.at<double>(0);
  f.ty = x.at<double>(1);
  f.theta = x.at<double>(2);
  f.worst = 0;
  for (int q : used) {
    const double px = f.tx - f.theta * centre[q].y, py = f.ty + f.theta * centre[q].x;
    f.worst = std::max(f.worst, std::hypot(px - shift[q].x, py - shift[q].y));
  }
  // A rotation shifts each quarter's features by different amounts, so the tolerance grows with
  // the motion: a fraction of its largest displacement at the points used.
  double largest = 0;
  for (int q : used) largest = std::max(largest, std::hypot(f.tx - f.theta * centre[q].y, f.ty + f.theta * centre[q].x));
  using L = RegistrationLimits;
  // The model holds for small turns only: a large theta fits any three shifts.
  f.ok = f.worst <= std::min(L::kAgreeMaxPx, std::max(L::kAgreePx, L::kAgreeShare * largest)) &&
         std::abs(f.theta) <= L::kMaxTurn;
  return f;
}

}  // namespace

int registrationFactor(int width) {
  return std::max(1, static_cast<int>(std::lround(double(width) / RegistrationLimits::kWidth)));
}

double movedLimitPx(int width) { return RegistrationLimits::kMovedPx * registrationFactor(width); }

std::vector<FrameMotion> registerFrames(const ImageStack& stack, int threads, PhaseCorrelator correlator) {
  const int n = stack.size();
  std::vector<FrameMotion> out(static_cast<std::size_t>(std::max(0, n)));
  const int f = registrationFactor(stack.width());
  const int w = stack.width() / f, h = stack.height() / f;
  if (n < 3 || stack.channels() != 1 || w < 16 || h < 16) return out;
  std::vector<cv::Mat> frames(static_cast<std::size_t>(n));
  const int workers = effectiveThreads(threads);
  parallelFor(static_cast<std::size_t>(n), 1, workers, [&](std::size_t b, std::size_t e) {
    for (std::size_t i = b; i < e; ++i) frames[i] = reduced(stack, static_cast<int>(i), f);
  });
  const cv::Mat median = medianOf(frames, workers);
  GradientBuffers referenceBuffers;
  const cv::Mat reference = gradient(median, referenceBuffers);
  const int qw = w / 2, qh = h / 2;
  cv::Mat window;
  cv::createHanningWindow(window, cv::Size(qw, qh), CV_32F);
  std::array<cv::Rect, 4> quarters;
  std::array<cv::Point2d, 4> centres;
  for (int q = 0; q < 4; ++q) {
    quarters[q] = cv::Rect((q % 2) * qw, (q / 2) * qh, qw, qh);  // centres[q] below
    centres[q] = {(q % 2) * qw + qw / 2.0 - w / 2.0, (q / 2) * qh + qh / 2.0 - h / 2.0};
  }
  // Each quarter's shift is that of its strongest edges: the point it applies to is the centroid
  // of the median's gradient there (weighted by the window), not the quarter's centre.
  // The median's quarters are every frame's reference: their spectra are computed once.
  std::vector<PhaseReference> referenceQuarters;
  std::array<cv::Mat, 4> openCvQuarters;  // PhaseCorrelator::OpenCv's references
  for (int q = 0; q < 4; ++q) {
    const cv::Mat quarter = reference(quarters[q]);
    if (correlator == PhaseCorrelator::Own) referenceQuarters.emplace_back(quarter, window);
    else openCvQuarters[q] = quarter.clone();
    const cv::Mat weight = quarter.mul(window);
    const cv::Moments m = cv::moments(weight);
    if (m.m00 > 0)
      centres[q] = {quarters[q].x + m.m10 / m.m00 - w / 2.0, quarters[q].y + m.m01 / m.m00 - h / 2.0};
  }
  std::vector<PhaseWorkspace> scratch(static_cast<std::size_t>(std::max(1, workers)));
  std::vector<GradientBuffers> buffers(scratch.size());
  parallelForWorkers(static_cast<std::size_t>(n), 1, workers, [&](int worker, std::size_t b, std::size_t e) {
    for (std::size_t i = b; i < e; ++i) {
      const cv::Mat& g = gradient(frames[i], buffers[static_cast<std::size_t>(worker)]);
      std::array<cv::Point2d, 4> shift;
      std::array<bool, 4> usable;
      std::array<double, 4> response;
      for (int q = 0; q < 4; ++q) {
        if (correlator == PhaseCorrelator::Own) {
          const PhaseShift s = referenceQuarters[q].correlate(g(quarters[q]), scratch[static_cast<std::size_t>(worker)]);
          shift[q] = s.shift;
          response[q] = s.response;
        } else {
          // Both clones: with sizes the DFT takes as they are, phaseCorrelate multiplies its
          // inputs by the window in place, which would change the shared reference.
          shift[q] = cv::phaseCorrelate(openCvQuarters[q].clone(), g(quarters[q]).clone(), window, &response[q]);
        }
        usable[q] = response[q] >= RegistrationLimits::kMinResponse;
      }
      // The quarters a motion is fitted to must, together, correlate clearly: three weak peaks
      // (shadows that moved with the light) can agree by chance.
      const auto clear = [&](const std::vector<int>& used) {
        double sum = 0;
        for (int q : used) sum += response[q];
        return sum >= RegistrationLimits::kMinMeanResponse * used.size();
      };
      // All four quarters, else the three that agree best; a quarter whose correlation has no
      // clear peak (nothing steady in it) is not used.
      Fit best;
      if (usable[0] && usable[1] && usable[2] && usable[3] && clear({0, 1, 2, 3}))
        best = fitMotion(centres, shift, {0, 1, 2, 3});
      if (!best.ok)
        for (int drop = 0; drop < 4; ++drop) {
          std::vector<int> used;
          for (int q = 0; q < 4; ++q)
            if (q != drop && usable[q]) used.push_back(q);
          if (used.size() < 3 || !clear(used)) continue;
          const Fit f3 = fitMotion(centres, shift, used);
          if (f3.ok && f3.worst < best.worst) best = f3;
        }
      if (!best.ok) continue;
      FrameMotion& m = out[i];
      m.measured = true;
      m.dx = best.tx * f;
      m.dy = best.ty * f;
      m.rotationDeg = best.theta * 180 / M_PI;
      for (int q = 0; q < 4; ++q)
        m.largestPx = std::max(m.largestPx, f * std::hypot(best.tx - best.theta * centres[q].y,
                                                            best.ty + best.theta * centres[q].x));
    }
  });
  return out;
}

}  // namespace surrogate::hrti
