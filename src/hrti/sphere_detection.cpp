#include "hrti/sphere_detection.h"

#include <opencv2/core.hpp>
#include <opencv2/imgproc.hpp>

#include <algorithm>
#include <cmath>
#include <sstream>

#include "core/error.h"
#include "core/parallel.h"
#include "core/text.h"
#include "hrti/accumulator_peaks.h"
#include "hrti/circle_fit.h"
#include "hrti/stack_median.h"

namespace surrogate::hrti {

namespace {

constexpr const char* kStep = "sphere detection";

cv::Mat toFloat(const Image& im) {
  cv::Mat m(im.height, im.width, CV_32F);
  for (int y = 0; y < im.height; ++y)
    for (int x = 0; x < im.width; ++x) m.at<float>(y, x) = im.at(x, y) / 65535.0f;
  return m;
}

// Values the full-resolution median gives over rows [y0, y1) and columns [x0, x1) (clipped to
// the frame), as floats in 0..1, and where that window lies.
struct FullWindow {
  cv::Mat values;
  int x0 = 0, y0 = 0;
};

FullWindow fullWindow(const StackMedian& median, int x0, int y0, int x1, int y1) {
  x0 = std::max(0, x0);
  y0 = std::max(0, y0);
  x1 = std::min(median.width(), x1);
  y1 = std::min(median.height(), y1);
  if (x1 <= x0 || y1 <= y0) return {cv::Mat(), x0, y0};
  return {toFloat(median.window({x0, y0, x1 - x0, y1 - y0})), x0, y0};
}

// The Gaussian blur (sigma 1) of the full-resolution median over [x0, x1) x [y0, y1), as a
// blur of the whole frame would give it there: the window is read with the kernel's reach
// around it (OpenCV's kernel for sigma 1 on floats is 9 wide), and reflected only at the frame's
// edges.
cv::Mat blurredWindow(const StackMedian& median, int x0, int y0, int x1, int y1) {
  constexpr int kReach = 4;
  const FullWindow padded = fullWindow(median, x0 - kReach, y0 - kReach, x1 + kReach, y1 + kReach);
  cv::Mat blurred;
  cv::GaussianBlur(padded.values, blurred, cv::Size(0, 0), 1.0);
  return blurred(cv::Rect(x0 - padded.x0, y0 - padded.y0, x1 - x0, y1 - y0)).clone();
}

struct Candidate {
  double x = 0, y = 0, r = 0, score = -1;
};

struct Gradients {
  cv::Mat gx, gy, mag;
};

Gradients gradients(const cv::Mat& coarse8) {
  cv::Mat smooth;
  cv::medianBlur(coarse8, smooth, 7);
  Gradients g;
  cv::Sobel(smooth, g.gx, CV_32F, 1, 0, 3);
  cv::Sobel(smooth, g.gy, CV_32F, 0, 1, 3);
  cv::magnitude(g.gx, g.gy, g.mag);
  return g;
}

// The circle Hough transform over radii [r0, r1] (coarse pixels) inside `area`. Each radius
// gets its own accumulator and yields its `perRadius` strongest local maxima (each found
// maximum's neighbourhood of r/2 is cleared before the next). The candidates are returned
// sorted by score (normalised by what a perfect circle of that radius reaches), ties in radius
// order, so the result is
// identical at any thread count.
std::vector<Candidate> hough(const Gradients& g, cv::Rect area, int r0, int r1, int perRadius, int threads) {
  double maxMag = 0;
  cv::minMaxLoc(g.mag(area), nullptr, &maxMag);
  struct Edge {
    float x, y, cosg, sing, weight;
  };
  std::vector<Edge> edges;
  for (int y = area.y; y < area.y + area.height; ++y) {
    for (int x = area.x; x < area.x + area.width; ++x) {
      const float m = g.mag.at<float>(y, x);
      if (m < 0.1 * maxMag) continue;  // faint gradients cost time and add only noise
      edges.push_back({float(x), float(y), g.gx.at<float>(y, x) / m, g.gy.at<float>(y, x) / m, m});
    }
  }
  if (edges.empty() || r1 < r0) return {};
  static const double kArc[] = {-M_PI / 12, -M_PI / 24, 0, M_PI / 24, M_PI / 12};
  double cosArc[5], sinArc[5];
  for (int k = 0; k < 5; ++k) {
    cosArc[k] = std::cos(kArc[k]);
    sinArc[k] = std::sin(kArc[k]);
  }
  // The accumulator value a perfect circle of radius r (unit edge strength) reaches at its
  // centre: each edge pixel's central vote lands there, the arc votes land 2 r sin(|phi|/2)
  // away and reach it only through the blur below (sigma 1). Dividing by this, not by the
  // circumference alone, keeps scores comparable across radii: otherwise the five votes of a
  // small circle pile up in one cell and a few pixels of any dark edge (a sphere's rim near
  // the frame) outscore the whole sphere (seen at 6000 px wide, radius 308 px).
  auto perfectCircle = [&](int r) {
    double sum = 0;
    for (int k = 0; k < 5; ++k) {
      const double d = 2 * r * std::sin(std::abs(kArc[k]) / 2);
      sum += std::exp(-d * d / 2);
    }
    return 2 * M_PI * r * sum;
  };
  const int radii = r1 - r0 + 1;
  std::vector<std::vector<Candidate>> perR(radii);
  parallelFor(radii, 1, effectiveThreads(threads), [&](std::size_t b, std::size_t e) {
    cv::Mat acc(area.height, area.width, CV_32F);
    for (std::size_t ri = b; ri < e; ++ri) {
      const int r = r0 + static_cast<int>(ri);
      acc.setTo(0);
      for (const Edge& ed : edges) {
        for (int k = 0; k < 5; ++k) {
          // Rotate the gradient direction by the arc angle; step against it (into the dark).
          const double dx = ed.cosg * cosArc[k] - ed.sing * sinArc[k];
          const double dy = ed.sing * cosArc[k] + ed.cosg * sinArc[k];
          const int cx = static_cast<int>(std::lround(ed.x - r * dx)) - area.x;
          const int cy = static_cast<int>(std::lround(ed.y - r * dy)) - area.y;
          if (cx >= 0 && cy >= 0 && cx < area.width && cy < area.height) acc.at<float>(cy, cx) += ed.weight;
        }
      }
      cv::GaussianBlur(acc, acc, cv::Size(5, 5), 1.0);
      AccumulatorPeaks peaks(acc);
      for (int m = 0; m < perRadius; ++m) {
        cv::Point at;
        const double value = peaks.strongest(&at);
        if (value <= 0) break;
        perR[ri].push_back({double(at.x + area.x), double(at.y + area.y), double(r), value / perfectCircle(r)});
        peaks.clearDisc(at, std::max(2, r / 2));
      }
    }
  });
  std::vector<Candidate> all;
  for (const auto& list : perR) all.insert(all.end(), list.begin(), list.end());
  std::stable_sort(all.begin(), all.end(), [](const Candidate& a, const Candidate& b) { return a.score > b.score; });
  return all;
}

// Sub-pixel edge points along rays from the centre, and the circle through them.
DetectedSphere refine(const StackMedian& median, Candidate start, double margin) {
  DetectedSphere out{start.x, start.y, start.r, 0};
  for (int pass = 0; pass < 2; ++pass) {
    const int x0 = std::max(0, static_cast<int>(out.cx - out.r - margin - 3));
    const int y0 = std::max(0, static_cast<int>(out.cy - out.r - margin - 3));
    const int x1 = std::min(median.width(), static_cast<int>(out.cx + out.r + margin + 4));
    const int y1 = std::min(median.height(), static_cast<int>(out.cy + out.r + margin + 4));
    if (x1 - x0 < 8 || y1 - y0 < 8) return out;
    const cv::Mat window = blurredWindow(median, x0, y0, x1, y1);
    cv::Mat gx, gy;
    cv::Sobel(window, gx, CV_32F, 1, 0, 3);
    cv::Sobel(window, gy, CV_32F, 0, 1, 3);
    auto sample = [&](const cv::Mat& m, double x, double y) {
      x -= x0;
      y -= y0;
      const int ix = static_cast<int>(std::floor(x)), iy = static_cast<int>(std::floor(y));
      if (ix < 0 || iy < 0 || ix + 1 >= m.cols || iy + 1 >= m.rows) return std::nan("");
      const double fx = x - ix, fy = y - iy;
      return (m.at<float>(iy, ix) * (1 - fx) + m.at<float>(iy, ix + 1) * fx) * (1 - fy) +
             (m.at<float>(iy + 1, ix) * (1 - fx) + m.at<float>(iy + 1, ix + 1) * fx) * fy;
    };
    std::vector<Point2> points;
    std::vector<double> strengths;
    constexpr int kRays = 360;
    constexpr double kStep = 0.25;
    for (int k = 0; k < kRays; ++k) {
      const double a = 2 * M_PI * k / kRays, ca = std::cos(a), sa = std::sin(a);
      double bestValue = -1, bestT = 0, before = 0, after = 0;
      std::vector<double> profile;
      for (double t = out.r - margin; t <= out.r + margin; t += kStep) {
        const double x = out.cx + t * ca, y = out.cy + t * sa;
        const double v = sample(gx, x, y) * ca + sample(gy, x, y) * sa;  // radial derivative
        profile.push_back(v);
      }
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
    out.confidence = double(fit.inliers) / kRays;
    margin = 3;
  }
  return out;
}

// A glossy black sphere is much darker than its surroundings: the mean inside 0.8 r against the
// mean of the ring between 1.15 r and 1.4 r. Round patches of texture fail this test.
bool isDarkDisc(const StackMedian& median, const DetectedSphere& s) {
  double inside = 0, outside = 0;
  int nIn = 0, nOut = 0;
  const int x0 = std::max(0, static_cast<int>(s.cx - 1.4 * s.r)), x1 = std::min(median.width() - 1, static_cast<int>(s.cx + 1.4 * s.r));
  const int y0 = std::max(0, static_cast<int>(s.cy - 1.4 * s.r)), y1 = std::min(median.height() - 1, static_cast<int>(s.cy + 1.4 * s.r));
  const FullWindow full = fullWindow(median, x0, y0, x1 + 1, y1 + 1);
  for (int y = y0; y <= y1; ++y) {
    for (int x = x0; x <= x1; ++x) {
      const double d = std::hypot(x - s.cx, y - s.cy) / s.r;
      if (d < 0.8) {
        inside += full.values.at<float>(y - full.y0, x - full.x0);
        ++nIn;
      } else if (d > 1.15 && d < 1.4) {
        outside += full.values.at<float>(y - full.y0, x - full.x0);
        ++nOut;
      }
    }
  }
  if (nIn == 0 || nOut == 0) return false;
  return inside / nIn < 0.6 * (outside / nOut);
}

std::vector<std::string> split(const std::string& s, char sep) {
  std::vector<std::string> out;
  std::stringstream ss(s);
  for (std::string item; std::getline(ss, item, sep);)
    if (!item.empty()) out.push_back(item);
  return out;
}

}  // namespace

std::vector<std::pair<std::string, std::string>> SphereDetectionOptions::toParameters() const {
  std::string r;
  for (const Rect& q : regions)
    r += (r.empty() ? "" : ";") + std::to_string(q.x) + "," + std::to_string(q.y) + "," +
         std::to_string(q.w) + "," + std::to_string(q.h);
  return {{"minRadius", formatNumber(minRadius)},       {"maxRadius", formatNumber(maxRadius)},
          {"regions", r},                               {"maxSpheres", std::to_string(maxSpheres)},
          {"minConfidence", formatNumber(minConfidence)}, {"coarseWidth", std::to_string(coarseWidth)}};
}

SphereDetectionOptions SphereDetectionOptions::fromParameters(
    const std::vector<std::pair<std::string, std::string>>& params) {
  SphereDetectionOptions o;
  for (const auto& [name, value] : params) {
    try {
      if (name == "minRadius") o.minRadius = std::stod(value);
      else if (name == "maxRadius") o.maxRadius = std::stod(value);
      else if (name == "maxSpheres") o.maxSpheres = std::stoi(value);
      else if (name == "minConfidence") o.minConfidence = std::stod(value);
      else if (name == "coarseWidth") o.coarseWidth = std::stoi(value);
      else if (name == "regions") {
        for (const std::string& region : split(value, ';')) {
          const auto v = split(region, ',');
          if (v.size() != 4) throw std::invalid_argument(region);
          o.regions.push_back({std::stoi(v[0]), std::stoi(v[1]), std::stoi(v[2]), std::stoi(v[3])});
        }
      } else {
        throw Error(ErrorKind::Input, name, kStep, "is not a parameter of sphere detection");
      }
    } catch (const std::logic_error&) {
      throw Error(ErrorKind::Input, name + "=" + value, kStep, "is not a valid value");
    }
  }
  if (o.minRadius < 3 || o.coarseWidth < 100 || o.maxSpheres < 1)
    throw Error(ErrorKind::Input, "", kStep, "sphere detection parameters out of range");
  return o;
}

std::vector<DetectedSphere> detectSpheres(const Image& median, const SphereDetectionOptions& o) {
  if (median.channels != 1 || median.empty())
    throw Error(ErrorKind::Internal, "", kStep, "needs a one-channel median image");
  // The median of a one-image stack is that image.
  return detectSpheres(StackMedian(MemoryImageStack({median}), o.coarseWidth, o.threads), o);
}

std::vector<DetectedSphere> detectSpheres(const StackMedian& median, const SphereDetectionOptions& o) {
  if (median.factor() != StackMedian::factorFor(median.width(), o.coarseWidth))
    throw Error(ErrorKind::Internal, "", kStep, "the median was reduced for another coarse width");
  const cv::Mat coarse = toFloat(median.coarse());
  double maxValue = 0;
  cv::minMaxLoc(coarse, nullptr, &maxValue);
  const double scale = median.factor();
  cv::Mat coarse8;
  coarse.convertTo(coarse8, CV_8U, maxValue > 0 ? 255.0 / maxValue : 1.0);
  const Gradients g = gradients(coarse8);
  const double maxRadius = o.maxRadius > 0 ? o.maxRadius : std::min(median.width(), median.height()) / 4.0;
  // Below 6 coarse pixels a circle is a handful of accumulator cells: noise, not a sphere.
  const int r0 = std::max(6, static_cast<int>(std::floor(o.minRadius / scale)));
  auto toFull = [&](Candidate c) {
    return Candidate{(c.x + 0.5) * scale - 0.5, (c.y + 0.5) * scale - 0.5, c.r * scale, c.score};
  };
  const double margin = 2 * scale + 4;

  // Candidates in order of Hough score; each is refined and must pass the tests below. A
  // candidate overlapping an accepted sphere is the same sphere at another radius.
  auto accept = [&](const std::vector<Candidate>& candidates, std::size_t wanted,
                    std::vector<DetectedSphere>& into) {
    constexpr std::size_t kMaxTried = 40;
    double firstScore = 0;
    std::size_t tried = 0;
    for (const Candidate& c : candidates) {
      if (into.size() >= wanted || tried >= kMaxTried) break;
      if (firstScore > 0 && c.score < firstScore / 3) break;
      const Candidate f = toFull(c);
      bool overlaps = false;
      for (const DetectedSphere& s : into) overlaps = overlaps || std::hypot(s.cx - f.x, s.cy - f.y) < s.r + f.r;
      if (overlaps) continue;
      ++tried;
      const DetectedSphere s = refine(median, f, margin);
      if (s.confidence < o.minConfidence || !isDarkDisc(median, s)) continue;
      bool duplicate = false;
      for (const DetectedSphere& q : into) duplicate = duplicate || std::hypot(s.cx - q.cx, s.cy - q.cy) < q.r;
      if (duplicate) continue;
      if (into.empty()) firstScore = c.score;
      into.push_back(s);
    }
  };

  std::vector<DetectedSphere> found;
  if (!o.regions.empty()) {
    for (const Rect& region : o.regions) {
      cv::Rect area(static_cast<int>(region.x / scale), static_cast<int>(region.y / scale),
                    static_cast<int>(std::ceil(region.w / scale)), static_cast<int>(std::ceil(region.h / scale)));
      area &= cv::Rect(0, 0, coarse.cols, coarse.rows);
      if (area.width < 8 || area.height < 8)
        throw Error(ErrorKind::Usage, "--sphere-roi", kStep, "the region is outside the image or too small");
      const int r1 = std::min(static_cast<int>(maxRadius / scale), std::max(area.width, area.height) / 2);
      std::vector<DetectedSphere> one;
      accept(hough(g, area, r0, r1, 3, o.threads), 1, one);
      found.insert(found.end(), one.begin(), one.end());
    }
  } else {
    const int r1 = static_cast<int>(maxRadius / scale);
    accept(hough(g, cv::Rect(0, 0, coarse.cols, coarse.rows), r0, r1, 4, o.threads),
           static_cast<std::size_t>(o.maxSpheres), found);
  }
  found.erase(std::remove_if(found.begin(), found.end(),
                             [&](const DetectedSphere& s) { return s.confidence < o.minConfidence; }),
              found.end());
  if (found.empty()) {
    throw Error(ErrorKind::Input, "", kStep,
                "no sphere was found in the median image; give its region with --sphere-roi "
                "x,y,w,h (repeat for each sphere) or its circle with --sphere cx,cy,r");
  }
  // Spheres from left to right, so their indices do not depend on detection order.
  std::sort(found.begin(), found.end(), [](const DetectedSphere& a, const DetectedSphere& b) {
    return a.cx != b.cx ? a.cx < b.cx : a.cy < b.cy;
  });
  return found;
}

}  // namespace surrogate::hrti
