#include "hrti/highlight_detection.h"

#include <opencv2/core.hpp>
#include <opencv2/imgproc.hpp>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <optional>
#include <sstream>

#include "core/error.h"
#include "core/parallel.h"
#include "core/text.h"
#include "hrti/stack_median.h"

namespace surrogate::hrti {

namespace {
constexpr const char* kStep = "highlight detection";
// Below this peak (of full scale) there is no highlight, only the sphere's dark body.
constexpr double kMinimumPeak = 0.05;
// The search and the measures read the discs within these fractions of the radius (see
// highlight_detection.h).
constexpr double kSearchedRadius = 0.9;
constexpr double kMeasuredRadius = 0.85;
}  // namespace

std::vector<std::pair<std::string, std::string>> HighlightOptions::toParameters() const {
  return {{"threshold", formatNumber(threshold)}, {"rimPixels", std::to_string(rimPixels)}};
}

HighlightOptions HighlightOptions::fromParameters(const std::vector<std::pair<std::string, std::string>>& params) {
  HighlightOptions o;
  for (const auto& [name, value] : params) {
    try {
      if (name == "threshold") o.threshold = std::stod(value);
      else if (name == "rimPixels") o.rimPixels = std::stoi(value);
      else throw Error(ErrorKind::Input, name, kStep, "is not a parameter of highlight detection");
    } catch (const std::logic_error&) {
      throw Error(ErrorKind::Input, name + "=" + value, kStep, "is not a valid value");
    }
  }
  if (!(o.threshold > 0 && o.threshold < 1) || o.rimPixels < 0)
    throw Error(ErrorKind::Input, "threshold", kStep, "must be between 0 and 1");
  return o;
}

namespace {

// 1 at or beyond `good`, 0 at or beyond `limit`, linear between (either direction).
double score(double value, double good, double limit) {
  const double t = (value - limit) / (good - limit);
  return std::clamp(t, 0.0, 1.0);
}

std::string percent(double fraction) {
  return std::to_string(static_cast<int>(std::lround(fraction * 100))) + " %";
}

std::string twoDecimals(double v) {
  char text[32];
  std::snprintf(text, sizeof text, "%.2f", v);
  return text;
}

}  // namespace

const char* flagName(HighlightFlag f) {
  switch (f) {
    case HighlightFlag::Ok: return "ok";
    case HighlightFlag::Multiple: return "multiple";
    case HighlightFlag::Manual: return "manual";
    case HighlightFlag::None: return "none";
    case HighlightFlag::Flat: return "flat";
    case HighlightFlag::Saturated: return "saturated";
    case HighlightFlag::Large: return "large";
    case HighlightFlag::NotCompact: return "not-compact";
    case HighlightFlag::Shaded: return "shaded";
    case HighlightFlag::Fixed: return "fixed";
    case HighlightFlag::Faint: return "faint";
  }
  return "none";
}

bool isUsable(HighlightFlag f) {
  return f == HighlightFlag::Ok || f == HighlightFlag::Multiple || f == HighlightFlag::Manual;
}

void judgeHighlight(Highlight& h, bool secondCandidate) {
  using L = HighlightLimits;
  const HighlightMeasures& m = h.measures;
  if (h.flag == HighlightFlag::None) {
    h.confidence = 0;
    h.reason = "nothing on the sphere is brighter in this image than in the others (its strongest rise is " +
               percent(h.peak) + " of full scale): the light was behind the sphere or did not fire";
    return;
  }
  const double contrast = score(m.contrast, L::kGoodContrast, L::kMinContrast);
  const double spread = score(m.spread, L::kGoodSpread, L::kMaxSpread);
  const double shape = std::min({score(m.compactness, L::kGoodCompactness, L::kMinCompactness),
                                 score(m.elongation, L::kGoodElongation, L::kMinElongation),
                                 score(m.fill, L::kGoodFill, L::kMinFill)});
  const double mirror = score(m.bodyRise, L::kGoodBodyRise, L::kMaxBodyRise);
  h.confidence = std::min({contrast, spread, shape, mirror, secondCandidate ? L::kMultipleCap : 1.0});
  h.reason.clear();
  if (h.peak >= L::kSaturatedLevel && m.saturated > L::kMaxSpread) {
    h.flag = HighlightFlag::Saturated;
    h.reason = percent(m.saturated) + " of the sphere is saturated (a highlight covers under " +
               percent(L::kMaxSpread) + "): the frame is overexposed or not of the sphere";
  } else if (m.contrast < L::kMinContrast) {
    h.flag = HighlightFlag::Flat;
    h.reason = "the sphere shows no peak: its body is " + percent(1 - m.contrast) +
               " as bright as its brightest pixel (beside a highlight it is under " +
               percent(1 - L::kMinContrast) + "): the frame is flat or featureless there";
  } else if (m.spread > L::kMaxSpread) {
    h.flag = HighlightFlag::Large;
    h.reason = percent(m.spread) + " of the sphere is brighter in this image than in the others by at least half "
               "the peak (a highlight covers under " + percent(L::kMaxSpread) + ")";
  } else if (m.bodyRise > L::kMaxBodyRise) {
    h.flag = HighlightFlag::Shaded;
    h.reason = "the sphere's body brightens with the light too (a quarter of it rises by " + percent(m.bodyRise) +
               " of the peak or more; on a mirror sphere only the highlight does, under " + percent(L::kMaxBodyRise) +
               "): a matte or painted round object, not a reflective sphere";
  } else if (m.elongation < L::kMinElongation) {
    h.flag = HighlightFlag::NotCompact;
    h.reason = "the brightest spot is a streak, not a highlight (roundness " + twoDecimals(m.elongation) +
               ", a highlight has at least " + twoDecimals(L::kMinElongation) + ")";
  } else if (m.fill < L::kMinFill) {
    h.flag = HighlightFlag::NotCompact;
    h.reason = "the brightest spot is a ring or a crescent, not a highlight (fill " + twoDecimals(m.fill) +
               ", a highlight has at least " + twoDecimals(L::kMinFill) + ")";
  } else if (m.compactness < L::kMinCompactness) {
    h.flag = HighlightFlag::NotCompact;
    h.reason = "the brightest spot is a single pixel or a speck, not a highlight (its blurred height is " +
               percent(m.compactness) + " of its peak; a highlight keeps at least " + percent(L::kMinCompactness) + ")";
  } else {
    h.flag = secondCandidate ? HighlightFlag::Multiple : HighlightFlag::Ok;
    if (secondCandidate)
      h.reason = "another spot on the sphere is nearly as bright; the brighter one was used";
    return;
  }
  h.confidence = 0;
}

namespace {

// A clipped highlight's centre: the point deepest inside the saturated plateau of its core.
struct PlateauCentre {
  double x = 0, y = 0;                 // full-image pixels
  double covXX = 0, covXY = 0, covYY = 0;  // pixels^2, see below
};
// A plateau whose deepest point is nearer its edge than this (pixels) is too small for its
// centre to be found to a fraction of a pixel (the distance transform moves in whole pixels):
// the core's centroid is used. Measured: 3 to 4.2 px on the generated captures' highlights and
// the chrome ball's (where the centroid is better), 10 to 15 px on PSBox's light probes.
constexpr double kMinPlateauDepth = 6;
// The deepest part of a plateau: points at least this share of the greatest depth.
constexpr double kPlateauTop = 0.8;

// Where the image is clipped, the core's centroid follows whatever is clipped with it: the glare
// streaks and scratches through a highlight that JPEG exports saturate with it (PSBox's light
// probes), which pulled the centroid 2 to 8 pixels along them. A streak is thinner than the
// highlight, so the point farthest from the plateau's edge (the centre of the largest disc
// inside it; OpenCV's exact Euclidean distance transform) is the highlight's centre; to a
// fraction of a pixel, the depth-weighted centroid of the points within kPlateauTop of the
// greatest depth. Its covariance is that of those points (each a unit square): how well the
// plateau's shape fixes its centre, long along a plateau that has no single deepest point.
// `values` the image, `core` the core's mask (CV_8U), both over the searched window at (offX, offY).
std::optional<PlateauCentre> plateauCentre(const cv::Mat& values, const cv::Mat& core, int offX, int offY) {
  cv::Mat clipped = (values >= static_cast<float>(HighlightLimits::kSaturatedLevel)) & core;
  if (cv::countNonZero(clipped) == 0) return std::nullopt;
  // The largest plateau (the first in row order among equals).
  cv::Mat labels, stats, centroids;
  const int count = cv::connectedComponentsWithStats(clipped, labels, stats, centroids, 8, CV_32S);
  int largest = 1;
  for (int l = 2; l < count; ++l)
    if (stats.at<int>(l, cv::CC_STAT_AREA) > stats.at<int>(largest, cv::CC_STAT_AREA)) largest = l;
  // Outside the window counts as outside the plateau. Only the plateau's bounding box is
  // transformed, with a ring of outside around it: a point of the plateau is nearer to that
  // ring than to anything outside beyond it (the ring's point with the outside point's
  // coordinates clamped to it is nearer along both axes), so the depths are those of the whole
  // window's (exact squared distances, their square roots), at a fraction of its pixels.
  // Positions below are the bordered window's, as when the whole window was transformed.
  const cv::Rect box(stats.at<int>(largest, cv::CC_STAT_LEFT), stats.at<int>(largest, cv::CC_STAT_TOP),
                     stats.at<int>(largest, cv::CC_STAT_WIDTH), stats.at<int>(largest, cv::CC_STAT_HEIGHT));
  cv::Mat plateau;
  cv::copyMakeBorder(labels(box) == largest, plateau, 1, 1, 1, 1, cv::BORDER_CONSTANT, 0);
  cv::Mat depth;
  cv::distanceTransform(plateau, depth, cv::DIST_L2, cv::DIST_MASK_PRECISE, CV_32F);
  double deepest = 0;
  cv::minMaxLoc(depth, nullptr, &deepest);
  if (deepest < kMinPlateauDepth) return std::nullopt;
  const double floor = kPlateauTop * deepest;
  double sum = 0, sx = 0, sy = 0, n = 0, px = 0, py = 0, pxx = 0, pyy = 0, pxy = 0;
  for (int by = 0; by < depth.rows; ++by)
    for (int bx = 0; bx < depth.cols; ++bx) {
      const double d = depth.at<float>(by, bx);
      if (d < floor) continue;
      const int x = bx + box.x, y = by + box.y;
      sum += d - floor;
      sx += (d - floor) * x;
      sy += (d - floor) * y;
      n += 1;
      px += x;
      py += y;
      pxx += double(x) * x;
      pyy += double(y) * y;
      pxy += double(x) * y;
    }
  if (!(sum > 0)) return std::nullopt;
  PlateauCentre c;
  c.x = sx / sum - 1 + offX;  // the border added above
  c.y = sy / sum - 1 + offY;
  const double mx = px / n, my = py / n;
  c.covXX = pxx / n - mx * mx + 1.0 / 12;
  c.covYY = pyy / n - my * my + 1.0 / 12;
  c.covXY = pxy / n - mx * my;
  return c;
}

}  // namespace

Highlight detectHighlight(const Image& crop, int cropX0, int cropY0, const DetectedSphere& s,
                          const HighlightOptions& o) {
  return detectHighlight(crop, nullptr, cropX0, cropY0, s, o);
}

Highlight detectHighlight(const Image& crop, const Image* median, int cropX0, int cropY0, const DetectedSphere& s,
                          const HighlightOptions& o) {
  if (median && (median->width != crop.width || median->height != crop.height))
    throw Error(ErrorKind::Internal, "", kStep, "the median crop differs in size from the image crop");
  Highlight h;
  h.x = s.cx;
  h.y = s.cy;
  const double inner = std::min(s.r - o.rimPixels, kSearchedRadius * s.r);
  const double measured = std::min(inner, kMeasuredRadius * s.r);
  const int x0 = std::max(0, static_cast<int>(std::floor(s.cx - inner)) - cropX0);
  const int y0 = std::max(0, static_cast<int>(std::floor(s.cy - inner)) - cropY0);
  const int x1 = std::min(crop.width - 1, static_cast<int>(std::ceil(s.cx + inner)) - cropX0);
  const int y1 = std::min(crop.height - 1, static_cast<int>(std::ceil(s.cy + inner)) - cropY0);
  if (x1 <= x0 || y1 <= y0 || inner <= 0) {
    judgeHighlight(h, false);
    return h;
  }
  const int w = x1 - x0 + 1, hh = y1 - y0 + 1;
  cv::Mat values(hh, w, CV_32F, cv::Scalar(0));  // the image, 0..1
  cv::Mat excess(hh, w, CV_32F, cv::Scalar(0));  // D: the image above the median
  cv::Mat inside(hh, w, CV_8U, cv::Scalar(0));   // 1 inside the searched disc, 2 inside the measured disc
  std::vector<float> disc;                         // image values of the measured disc
  float highestRise = 0;
  const double inner2 = inner * inner, measured2 = measured * measured;
  for (int y = 0; y < hh; ++y) {
    const double dy = y + y0 + cropY0 - s.cy;
    for (int x = 0; x < w; ++x) {
      const double dx = x + x0 + cropX0 - s.cx;
      const double d2 = dx * dx + dy * dy;
      if (d2 > inner2) continue;
      const float v = crop.at(x + x0, y + y0) / 65535.0f;
      const float m = median ? median->at(x + x0, y + y0) / 65535.0f : 0.0f;
      const float rise = std::max(0.0f, v - m);
      values.at<float>(y, x) = v;
      excess.at<float>(y, x) = rise;
      highestRise = std::max(highestRise, rise);
      inside.at<std::uint8_t>(y, x) = d2 <= measured2 ? 2 : 1;
      if (d2 <= measured2) disc.push_back(v);
    }
  }
  // The blur cannot raise the peak: with no rise of kMinimumPeak anywhere there is none to find
  // (most of the frames a circle that is not a sphere shows, checked without blurring them).
  if (disc.empty() || highestRise < kMinimumPeak) {
    h.peak = highestRise;
    judgeHighlight(h, false);  // flag None
    return h;
  }
  const double sigma = std::clamp(s.r / 150.0, 0.8, 4.0);
  cv::Mat blurred;
  cv::GaussianBlur(excess, blurred, cv::Size(0, 0), sigma, sigma, cv::BORDER_CONSTANT);
  blurred.setTo(0, inside == 0);
  double peak = 0;
  cv::Point at;
  cv::minMaxLoc(blurred, nullptr, &peak, nullptr, &at);  // the first maximum in row order
  if (peak < kMinimumPeak) {
    h.peak = highestRise;
    judgeHighlight(h, false);  // flag None
    return h;
  }
  // The image around the peak: its brightest value, and the highest rise above the median.
  const int reach = static_cast<int>(std::ceil(2 * sigma));
  const cv::Rect near = cv::Rect(at.x - reach, at.y - reach, 2 * reach + 1, 2 * reach + 1) & cv::Rect(0, 0, w, hh);
  double rawPeak = 0, brightest = 0;
  cv::minMaxLoc(excess(near), nullptr, &rawPeak);
  cv::minMaxLoc(values(near), nullptr, &brightest);
  h.measures.compactness = rawPeak > 0 ? std::min(1.0, peak / rawPeak) : 0;

  // The sphere's body: the median of the measured disc (the highlight is a small part of it).
  std::nth_element(disc.begin(), disc.begin() + disc.size() / 2, disc.end());
  const double body = disc[disc.size() / 2];
  int aboveHalfway = 0, saturated = 0;
  for (int y = 0; y < hh; ++y)
    for (int x = 0; x < w; ++x) {
      if (inside.at<std::uint8_t>(y, x) != 2) continue;
      aboveHalfway += blurred.at<float>(y, x) >= static_cast<float>(peak / 2);
      saturated += values.at<float>(y, x) >= static_cast<float>(HighlightLimits::kSaturatedLevel);
    }
  // How much the rest of the sphere rises in this image: the upper quartile of D over the
  // measured disc, against the peak. A mirror sphere's body does not follow the light (only
  // its highlight does); a matte or painted round object's shading does.
  std::vector<float> rises;
  rises.reserve(disc.size());
  for (int y = 0; y < hh; ++y)
    for (int x = 0; x < w; ++x)
      if (inside.at<std::uint8_t>(y, x) == 2) rises.push_back(excess.at<float>(y, x));
  std::nth_element(rises.begin(), rises.begin() + rises.size() * 3 / 4, rises.end());
  h.measures.bodyRise = std::min(1.0, rises[rises.size() * 3 / 4] / peak);
  h.measures.contrast = brightest > 0 ? std::max(0.0, (brightest - body) / brightest) : 0;
  h.measures.spread = double(aboveHalfway) / disc.size();
  h.measures.saturated = double(saturated) / disc.size();
  h.peak = std::max(peak, brightest);

  // The core: the 8-connected pixels around the peak at `threshold` of it; others are candidates.
  cv::Mat mask = blurred >= static_cast<float>(o.threshold * peak);
  cv::Mat labels;
  const int count = cv::connectedComponents(mask, labels, 8, CV_32S);
  const int chosen = labels.at<int>(at.y, at.x);
  struct Component {
    double sum = 0, sx = 0, sy = 0, peak = 0;
    double px = 0, py = 0, pxx = 0, pyy = 0, pxy = 0;  // unweighted position moments
    int area = 0, saturated = 0;  // pixels, and those whose image value is saturated
  };
  std::vector<Component> comps(count);
  for (int y = 0; y < hh; ++y) {
    for (int x = 0; x < w; ++x) {
      const int l = labels.at<int>(y, x);
      if (l == 0) continue;
      const double v = blurred.at<float>(y, x);
      // The centroid's weight is the height above the core's edge, which is 0 there: a pixel the
      // grid puts just inside or just outside the edge barely moves it (weighted by B itself, a
      // round spot's centroid was off by 0.09 px, tests/hrti/test_fit_uncertainty.cpp).
      const double above = std::max(0.0, v - o.threshold * peak);
      Component& c = comps[l];
      c.sum += above;
      c.sx += above * (x + x0 + cropX0);
      c.sy += above * (y + y0 + cropY0);
      c.peak = std::max(c.peak, v);
      c.area++;
      c.saturated += values.at<float>(y, x) >= static_cast<float>(HighlightLimits::kSaturatedLevel);
      c.px += x;
      c.py += y;
      c.pxx += double(x) * x;
      c.pyy += double(y) * y;
      c.pxy += double(x) * y;
    }
  }
  const Component& c = comps[chosen];
  h.components = count - 1;
  h.x = c.sx / c.sum;
  h.y = c.sy / c.sum;
  h.flag = HighlightFlag::Ok;
  // The shape of the core: covariance of its pixel positions, each pixel a unit square
  // (variance 1/12 along each axis).
  const double n = c.area;
  const double mx = c.px / n, my = c.py / n;
  const double vxx = c.pxx / n - mx * mx + 1.0 / 12, vyy = c.pyy / n - my * my + 1.0 / 12;
  const double vxy = c.pxy / n - mx * my;
  const double det = std::max(vxx * vyy - vxy * vxy, 1e-12);
  h.measures.area = c.area;
  h.measures.fill = std::min(1.0, n / (4 * M_PI * std::sqrt(det)));
  const double mean = (vxx + vyy) / 2, diff = std::sqrt(std::max(0.0, mean * mean - det));
  const double l1 = mean + diff + HighlightLimits::kBlurPx2;
  const double l2 = std::max(0.0, mean - diff) + HighlightLimits::kBlurPx2;
  h.measures.elongation = std::sqrt(l2 / l1);
  // The centre's covariance as an estimate (Highlight::covXX..): the core's own covariance
  // divided by the number of independent looks at it, the blur's footprints (4 pi sigma^2
  // pixels each) in the core's unsaturated pixels. Where the image is clipped the plateau hides
  // where the peak is, so a saturated core counts as one look: the centre anywhere in it. An
  // elongated core is uncertain along its length, which Sigma carries.
  const double looks = std::max(1.0, (c.area - c.saturated) / (4 * M_PI * sigma * sigma));
  h.covXX = vxx / looks;
  h.covYY = vyy / looks;
  h.covXY = vxy / looks;
  if (const auto plateau = plateauCentre(values, labels == chosen, x0 + cropX0, y0 + cropY0)) {
    h.x = plateau->x;
    h.y = plateau->y;
    h.covXX = plateau->covXX;
    h.covXY = plateau->covXY;
    h.covYY = plateau->covYY;
  }
  bool second = false;
  for (int l = 1; l < count; ++l)
    if (l != chosen && comps[l].peak >= HighlightLimits::kSecondPeak * peak) second = true;
  judgeHighlight(h, second);
  return h;
}

Rect highlightWindow(const DetectedSphere& s, int width, int height) {
  const int y0 = std::clamp(static_cast<int>(std::floor(s.cy - s.r)) - 2, 0, height);
  const int y1 = std::clamp(static_cast<int>(std::ceil(s.cy + s.r)) + 3, 0, height);
  const int x0 = std::clamp(static_cast<int>(std::floor(s.cx - s.r)) - 2, 0, width);
  const int x1 = std::clamp(static_cast<int>(std::ceil(s.cx + s.r)) + 3, 0, width);
  if (y1 <= y0 || x1 <= x0) return {0, 0, 0, 0};
  return {x0, y0, x1 - x0, y1 - y0};
}

std::vector<std::vector<Highlight>> detectHighlights(const ImageStack& stack,
                                                     const std::vector<DetectedSphere>& spheres,
                                                     const HighlightOptions& o, int threads,
                                                     const StackMedian* median) {
  if (stack.channels() != 1) throw Error(ErrorKind::Internal, "", kStep, "needs a luminance stack");
  // The median of fewer than three images is one of them: it would cancel the highlight.
  const bool useMedian = median && stack.size() >= 3;
  std::vector<Rect> windows;
  std::vector<Image> medians;
  for (const DetectedSphere& s : spheres) {
    windows.push_back(highlightWindow(s, stack.width(), stack.height()));
    medians.push_back(useMedian && windows.back().w > 0 ? median->window(windows.back()) : Image());
  }
  std::vector<std::vector<Highlight>> out(stack.size(), std::vector<Highlight>(spheres.size()));
  parallelFor(stack.size(), 1, effectiveThreads(threads), [&](std::size_t b, std::size_t e) {
    for (std::size_t i = b; i < e; ++i) {
      for (std::size_t k = 0; k < spheres.size(); ++k) {
        const Rect& r = windows[k];
        if (r.w <= 0) continue;
        Image window(r.w, r.h, 1);
        stack.readWindow(static_cast<int>(i), r.x, r.y, r.x + r.w, r.y + r.h, window.pixels.data());
        out[i][k] = detectHighlight(window, useMedian ? &medians[k] : nullptr, r.x, r.y, spheres[k], o);
      }
    }
  });
  return out;
}

}  // namespace surrogate::hrti
