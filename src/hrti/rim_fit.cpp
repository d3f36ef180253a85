#include "hrti/rim_fit.h"

#include <opencv2/imgproc.hpp>

#include <algorithm>
#include <cmath>
#include <vector>

#include "core/cpu_features.h"
#include "hrti/circle_fit.h"
#include "hrti/stack_median.h"

#if defined(__x86_64__) && defined(__GNUC__)
#include <immintrin.h>
#endif

namespace surrogate::hrti {

namespace {
// medianToFloat into `m` (im.height x im.width floats, possibly a view into a larger matrix).
void medianToFloatInto(const Image& im, cv::Mat m) {
  for (int y = 0; y < im.height; ++y)
    for (int x = 0; x < im.width; ++x) m.at<float>(y, x) = im.at(x, y) / 65535.0f;
}
}  // namespace

cv::Mat medianToFloat(const Image& im) {
  cv::Mat m(im.height, im.width, CV_32F);
  medianToFloatInto(im, m);
  return m;
}

MedianWindow medianWindow(const StackMedian& median, int x0, int y0, int x1, int y1) {
  x0 = std::max(0, x0);
  y0 = std::max(0, y0);
  x1 = std::min(median.width(), x1);
  y1 = std::min(median.height(), y1);
  if (x1 <= x0 || y1 <= y0) return {cv::Mat(), x0, y0};
  return {medianToFloat(median.window({x0, y0, x1 - x0, y1 - y0})), x0, y0};
}

namespace {

// The blur's reach (pixels): OpenCV's kernel for sigma 1 on floats is 9 wide.
constexpr int kBlurReach = 4;
// How far beyond the distances a pass samples its profiles depend on the median (pixels): a
// sample interpolates the gradients of the 2 x 2 pixels around it (1 pixel), each the 3 x 3 Sobel
// of the blurred median (1 more), each blurred over kBlurReach more: 6 pixels along each axis,
// 6 sqrt 2 < 8.5 in any direction, with one to spare.
constexpr double kProfileReach = 9.5;

// The window whose gradients a pass over the circle (cx, cy, r) searched within `margin` reads:
// rows [y0, y1) and columns [x0, x1) of the frame; none (false) when under 8 pixels wide or high.
struct PassWindow {
  int x0, y0, x1, y1;
};
bool passWindow(const StackMedian& median, double cx, double cy, double r, double margin, PassWindow& w) {
  w.x0 = std::max(0, static_cast<int>(cx - r - margin - 3));
  w.y0 = std::max(0, static_cast<int>(cy - r - margin - 3));
  w.x1 = std::min(median.width(), static_cast<int>(cx + r + margin + 4));
  w.y1 = std::min(median.height(), static_cast<int>(cy + r + margin + 4));
  return w.x1 - w.x0 >= 8 && w.y1 - w.y0 >= 8;
}

// The window with the blur's reach around it, clipped to the frame: the median read.
Rect paddedWindow(const StackMedian& median, const PassWindow& w) {
  const int x0 = std::max(0, w.x0 - kBlurReach), y0 = std::max(0, w.y0 - kBlurReach);
  const int x1 = std::min(median.width(), w.x1 + kBlurReach), y1 = std::min(median.height(), w.y1 + kBlurReach);
  return {x0, y0, x1 - x0, y1 - y0};
}

// The parts of `padded` a pass reads (rimReads).
std::vector<Rect> passReads(const Rect& padded, double cx, double cy, double r, double margin) {
  // The distances from the centre the profiles sample: r - margin .. r + margin, or, when the
  // margin exceeds the radius, from the centre itself (negative distances lie across it).
  const double inner = std::max(0.0, r - margin) - kProfileReach, outer = r + margin + kProfileReach;
  constexpr int kTile = StackMedian::kTile;
  std::vector<Rect> reads;
  const int xEnd = padded.x + padded.w, yEnd = padded.y + padded.h;
  for (int ty = padded.y / kTile * kTile; ty < yEnd; ty += kTile) {
    const int ay = std::max(padded.y, ty), by = std::min(yEnd, ty + kTile) - 1;  // rows, inclusive
    const double nearY = std::clamp(cy, double(ay), double(by)) - cy, farY = std::max(cy - ay, by - cy);
    bool open = false;  // whether the last tile of this row is read (then the next one extends it)
    for (int tx = padded.x / kTile * kTile; tx < xEnd; tx += kTile) {
      const int ax = std::max(padded.x, tx), bx = std::min(xEnd, tx + kTile) - 1;
      const double nearX = std::clamp(cx, double(ax), double(bx)) - cx, farX = std::max(cx - ax, bx - cx);
      const bool read = std::hypot(nearX, nearY) <= outer && std::hypot(farX, farY) >= inner;
      if (read && open)
        reads.back().w = bx + 1 - reads.back().x;
      else if (read)
        reads.push_back({ax, ay, bx + 1 - ax, by + 1 - ay});
      open = read;
    }
  }
  return reads;
}

// The Gaussian blur (sigma 1) of the full-resolution median over the pass window, as a blur of
// the whole frame would give it there: the median is read with the blur's reach around it
// (`padded`), and reflected only at the frame's edges. Only the parts `reads` are read, the rest
// left 0: the pixels the profiles depend on lie in them, and any value elsewhere changes neither
// those pixels' blur nor their gradients (the window's size, which decides how OpenCV's filters
// run over it, stays the same). A view into the blur of the larger window, not a copy: filters
// that read it must take it as a whole image (cv::BORDER_ISOLATED), which gives a copy's values.
cv::Mat blurredWindow(const StackMedian& median, const PassWindow& w, const Rect& padded,
                      const std::vector<Rect>& reads) {
  cv::Mat values = cv::Mat::zeros(padded.h, padded.w, CV_32F);
  for (const Rect& part : reads)
    medianToFloatInto(median.window(part), values(cv::Rect(part.x - padded.x, part.y - padded.y, part.w, part.h)));
  cv::Mat blurred;
  cv::GaussianBlur(values, blurred, cv::Size(0, 0), 1.0);
  return blurred(cv::Rect(w.x0 - padded.x, w.y0 - padded.y, w.x1 - w.x0, w.y1 - w.y0));
}

// How far (pixels, or a share of the radius when more) an edge point may lie from the fitted
// circle and count as the rim.
constexpr double kRimTolerance = 1.0, kRimToleranceShare = 0.01;

// Independent arcs of the rim assumed at most (see rimSigmas).
constexpr double kIndependentArcs = 12;
// Edge points closer than this along the rim (pixels) share their errors: the sigma-1 blur and
// the 3x3 Sobel make the gradient of a pixel from a neighbourhood about 3 pixels wide.
constexpr double kCorrelationLength = 3;

// The standard errors of the rim fit (DetectedSphere::centreSigmaPx, radiusSigmaPx): the
// Gauss-Newton covariance s^2 (J^T J)^-1 of the fit (hrti/circle_fit.h), its variances inflated
// when neighbouring rays are closer than kCorrelationLength (a small circle's 360 rays
// sample the same pixels), and not below what kIndependentArcs independent arcs with the
// residuals' spread s give (2 s^2 / n for each centre axis, s^2 / n for the radius: for n
// points spread evenly round a circle): the edge's bias changes with the background, the
// light and the stand along whole arcs, and those errors do not average out over rays.
void rimSigmas(const CircleFit& fit, int rays, DetectedSphere& out) {
  if (fit.inliers < 4) return;
  const double spacing = 2 * M_PI * fit.r / rays;
  const double inflation = std::max(1.0, kCorrelationLength / std::max(spacing, 1e-9));
  const double arcs = std::min(kIndependentArcs, double(fit.inliers));
  const double s2 = fit.residualSd * fit.residualSd;
  const double centre2 = 0.5 * (fit.sigmaCx * fit.sigmaCx + fit.sigmaCy * fit.sigmaCy) * inflation;
  out.centreSigmaPx = std::sqrt(std::max(centre2, 2 * s2 / arcs));
  out.radiusSigmaPx = std::sqrt(std::max(fit.sigmaR * fit.sigmaR * inflation, s2 / arcs));
}

// A ray whose rim point lies within this of the frame's edge (pixels) is not searched.
constexpr double kFrameInset = 2;

// The rays from the centre, and the step along each (pixels).
constexpr int kRays = 360;
constexpr double kStep = 0.25;

// The rays' cosines and sines, computed once: every pass of every circle takes the same 360.
struct RayDirections {
  std::vector<double> cos, sin;
};
const RayDirections& rays() {
  static const RayDirections table = [] {
    RayDirections r{std::vector<double>(kRays), std::vector<double>(kRays)};
    for (int k = 0; k < kRays; ++k) {
      r.cos[k] = std::cos(2 * M_PI * k / kRays);
      r.sin[k] = std::sin(2 * M_PI * k / kRays);
    }
    return r;
  }();
  return table;
}

}  // namespace

namespace detail {

void radialProfilePlain(const RimGradients& g, double cx, double cy, double ca, double sa, const double* ts,
                        std::size_t n, double* out) {
  for (std::size_t i = 0; i < n; ++i) {
    const double x = cx + ts[i] * ca - g.x0, y = cy + ts[i] * sa - g.y0;
    const int ix = static_cast<int>(std::floor(x)), iy = static_cast<int>(std::floor(y));
    if (ix < 0 || iy < 0 || ix + 1 >= g.cols || iy + 1 >= g.rows) {
      out[i] = std::nan("");
      continue;
    }
    const double fx = x - ix, fy = y - iy;
    const std::size_t at = static_cast<std::size_t>(iy) * g.cols + ix;
    const float* gx0 = g.gx + at;
    const float* gx1 = gx0 + g.cols;
    const float* gy0 = g.gy + at;
    const float* gy1 = gy0 + g.cols;
    const double vx = (gx0[0] * (1 - fx) + gx0[1] * fx) * (1 - fy) + (gx1[0] * (1 - fx) + gx1[1] * fx) * fy;
    const double vy = (gy0[0] * (1 - fx) + gy0[1] * fx) * (1 - fy) + (gy1[0] * (1 - fx) + gy1[1] * fx) * fy;
    out[i] = vx * ca + vy * sa;
  }
}

#if defined(__x86_64__) && defined(__GNUC__)
// The bilinear interpolation of `p` at four places: rows `top` and `top` + `cols` of the 2 x 2
// pixels (each row's two floats gathered as one 8-byte element), the fractions fx, fy and their
// complements cfx = 1 - fx, cfy = 1 - fy, in the plain variant's order.
__attribute__((target("avx2"))) inline void gatheredPairs(const float* p, __m128i at, __m256d& left, __m256d& right) {
  const __m256i pairs = _mm256_i32gather_epi64(reinterpret_cast<const long long*>(p), at, 4);
  const __m256 split = _mm256_permutevar8x32_ps(_mm256_castsi256_ps(pairs), _mm256_setr_epi32(0, 2, 4, 6, 1, 3, 5, 7));
  left = _mm256_cvtps_pd(_mm256_castps256_ps128(split));
  right = _mm256_cvtps_pd(_mm256_extractf128_ps(split, 1));
}
__attribute__((target("avx2"))) inline __m256d interpolated4(const float* p, __m128i top, __m128i cols, __m256d fx,
                                                             __m256d fy, __m256d cfx, __m256d cfy) {
  __m256d p00, p01, p10, p11;
  gatheredPairs(p, top, p00, p01);
  gatheredPairs(p, _mm_add_epi32(top, cols), p10, p11);
  const __m256d upper = _mm256_add_pd(_mm256_mul_pd(p00, cfx), _mm256_mul_pd(p01, fx));
  const __m256d lower = _mm256_add_pd(_mm256_mul_pd(p10, cfx), _mm256_mul_pd(p11, fx));
  return _mm256_add_pd(_mm256_mul_pd(upper, cfy), _mm256_mul_pd(lower, fy));
}

// Four distances at a time, the pixels gathered; "avx2" alone: the compiler may not fuse a
// multiply and an add (that needs "fma"), so every product and sum rounds as in the plain
// variant. floor(x) is the whole number the plain variant converts to int and back.
__attribute__((target("avx2"))) void radialAvx2(const RimGradients& g, double cx, double cy, double ca, double sa,
                                                const double* ts, std::size_t n, double* out) {
  const __m256d vcx = _mm256_set1_pd(cx), vcy = _mm256_set1_pd(cy), vca = _mm256_set1_pd(ca), vsa = _mm256_set1_pd(sa);
  const __m256d x0 = _mm256_set1_pd(g.x0), y0 = _mm256_set1_pd(g.y0), one = _mm256_set1_pd(1.0);
  const __m256d nan = _mm256_set1_pd(std::nan(""));
  const __m128i minusOne = _mm_set1_epi32(-1), cols = _mm_set1_epi32(g.cols);
  const __m128i lastX = _mm_set1_epi32(g.cols - 1), lastY = _mm_set1_epi32(g.rows - 1);
  std::size_t i = 0;
  for (; i + 4 <= n; i += 4) {
    const __m256d t = _mm256_loadu_pd(ts + i);
    const __m256d x = _mm256_sub_pd(_mm256_add_pd(vcx, _mm256_mul_pd(t, vca)), x0);
    const __m256d y = _mm256_sub_pd(_mm256_add_pd(vcy, _mm256_mul_pd(t, vsa)), y0);
    const __m256d wx = _mm256_floor_pd(x), wy = _mm256_floor_pd(y);
    const __m128i ix = _mm256_cvttpd_epi32(wx), iy = _mm256_cvttpd_epi32(wy);
    const __m128i inside = _mm_and_si128(_mm_and_si128(_mm_cmpgt_epi32(ix, minusOne), _mm_cmpgt_epi32(iy, minusOne)),
                                         _mm_and_si128(_mm_cmpgt_epi32(lastX, ix), _mm_cmpgt_epi32(lastY, iy)));
    if (_mm_movemask_epi8(inside) == 0) {
      _mm256_storeu_pd(out + i, nan);
      continue;
    }
    // Outside the window the pixel (0, 0) is read, and its value replaced by NaN below.
    const __m128i at00 = _mm_and_si128(inside, _mm_add_epi32(_mm_mullo_epi32(iy, cols), ix));
    const __m256d fx = _mm256_sub_pd(x, wx), fy = _mm256_sub_pd(y, wy);
    const __m256d cfx = _mm256_sub_pd(one, fx), cfy = _mm256_sub_pd(one, fy);  // 1 - fx, 1 - fy
    const __m256d vx = interpolated4(g.gx, at00, cols, fx, fy, cfx, cfy);
    const __m256d vy = interpolated4(g.gy, at00, cols, fx, fy, cfx, cfy);
    const __m256d v = _mm256_add_pd(_mm256_mul_pd(vx, vca), _mm256_mul_pd(vy, vsa));
    _mm256_storeu_pd(out + i, _mm256_blendv_pd(nan, v, _mm256_castsi256_pd(_mm256_cvtepi32_epi64(inside))));
  }
  radialProfilePlain(g, cx, cy, ca, sa, ts + i, n - i, out + i);
}
#endif

bool radialProfileAvx2(const RimGradients& g, double cx, double cy, double ca, double sa, const double* ts,
                       std::size_t n, double* out) {
#if defined(__x86_64__) && defined(__GNUC__)
  radialAvx2(g, cx, cy, ca, sa, ts, n, out);
  return true;
#else
  (void)g, (void)cx, (void)cy, (void)ca, (void)sa, (void)ts, (void)n, (void)out;
  return false;
#endif
}

}  // namespace detail

std::vector<Rect> rimReads(const StackMedian& median, double cx, double cy, double r, double margin) {
  PassWindow w;
  if (!passWindow(median, cx, cy, r, margin, w)) return {};
  return passReads(paddedWindow(median, w), cx, cy, r, margin);
}

namespace {

// refineRim; `whole`: each pass reads its whole window (detail::refineRimWholeWindow).
DetectedSphere refine(const StackMedian& median, double cx, double cy, double r, double margin, bool ofVisible,
                      bool whole) {
  DetectedSphere out{cx, cy, r, 0};
  const bool avx2 = cpuHasAvx2();
  // Each pass searches the rim within `margin` of the last circle, the margin shrinking to 3 px.
  for (int pass = 0; pass < 3; ++pass) {
    PassWindow w;
    if (!passWindow(median, out.cx, out.cy, out.r, margin, w)) return out;
    const Rect padded = paddedWindow(median, w);
    const cv::Mat window = blurredWindow(median, w, padded,
                                         whole ? std::vector<Rect>{padded} : passReads(padded, out.cx, out.cy, out.r, margin));
    cv::Mat gx, gy;
    cv::Sobel(window, gx, CV_32F, 1, 0, 3, 1, 0, cv::BORDER_REFLECT_101 | cv::BORDER_ISOLATED);
    cv::Sobel(window, gy, CV_32F, 0, 1, 3, 1, 0, cv::BORDER_REFLECT_101 | cv::BORDER_ISOLATED);
    const detail::RimGradients grad{gx.ptr<float>(), gy.ptr<float>(), gx.cols, gx.rows, w.x0, w.y0};
    // The distances along a ray, the same for every ray.
    std::vector<double> ts;
    for (double t = out.r - margin; t <= out.r + margin; t += kStep) ts.push_back(t);
    std::vector<Point2> points;
    std::vector<double> strengths;
    std::vector<double> profile(ts.size());
    int visible = 0;
    for (int k = 0; k < kRays; ++k) {
      const double ca = rays().cos[k], sa = rays().sin[k];
      const double rimX = out.cx + out.r * ca, rimY = out.cy + out.r * sa;
      if (rimX < kFrameInset || rimY < kFrameInset || rimX > median.width() - 1 - kFrameInset ||
          rimY > median.height() - 1 - kFrameInset)
        continue;
      ++visible;
      double bestValue = -1, bestT = 0, before = 0, after = 0;
      if (!avx2 || !detail::radialProfileAvx2(grad, out.cx, out.cy, ca, sa, ts.data(), ts.size(), profile.data()))
        detail::radialProfilePlain(grad, out.cx, out.cy, ca, sa, ts.data(), ts.size(), profile.data());
      for (std::size_t i = 1; i + 1 < profile.size(); ++i) {
        if (std::isnan(profile[i])) continue;
        if (profile[i] > bestValue) {
          bestValue = profile[i];
          bestT = out.r - margin + i * kStep;
          before = profile[i - 1];
          after = profile[i + 1];
        }
      }
      if (!(bestValue > 0) || std::isnan(before) || std::isnan(after)) continue;
      const double denom = before - 2 * bestValue + after;
      const double offset = denom < 0 ? 0.5 * (before - after) / denom : 0;
      const double t = bestT + std::clamp(offset, -0.5, 0.5) * kStep;
      points.push_back({out.cx + t * ca, out.cy + t * sa});
      strengths.push_back(bestValue);
    }
    if (points.size() < 20) return out;
    // Rays where the outline is faint (the sphere's own shadow, a dark background) are left out.
    std::vector<double> sorted = strengths;
    std::nth_element(sorted.begin(), sorted.begin() + sorted.size() / 2, sorted.end());
    const double floor = 0.25 * sorted[sorted.size() / 2];
    std::vector<Point2> strong;
    for (std::size_t i = 0; i < points.size(); ++i)
      if (strengths[i] >= floor) strong.push_back(points[i]);
    const CircleFit fit = fitCircle(strong, 1.0);
    if (!fit.ok) return out;
    out.cx = fit.cx;
    out.cy = fit.cy;
    out.r = fit.r;
    rimSigmas(fit, kRays, out);
    // The share of all rays whose edge lies on the circle, within a pixel (more for a large
    // circle, whose rim is blurred over more pixels): the fit's own inliers are judged against
    // the spread of the points, which on texture grows until every ray is an inlier.
    const double onRim = std::max(kRimTolerance, kRimToleranceShare * fit.r);
    int onCircle = 0;
    for (const Point2& q : strong) onCircle += std::abs(std::hypot(q.x - fit.cx, q.y - fit.cy) - fit.r) <= onRim;
    out.confidence = double(onCircle) / (ofVisible ? std::max(1, visible) : kRays);
    margin = std::max(3.0, margin / 3);
  }
  return out;
}

}  // namespace

DetectedSphere refineRim(const StackMedian& median, double cx, double cy, double r, double margin, bool ofVisible) {
  return refine(median, cx, cy, r, margin, ofVisible, false);
}

DetectedSphere detail::refineRimWholeWindow(const StackMedian& median, double cx, double cy, double r, double margin,
                                            bool ofVisible) {
  return refine(median, cx, cy, r, margin, ofVisible, true);
}

}  // namespace surrogate::hrti
