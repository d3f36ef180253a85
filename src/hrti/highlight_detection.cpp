#include "hrti/highlight_detection.h"

#include <opencv2/core.hpp>
#include <opencv2/imgproc.hpp>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <sstream>

#include "core/error.h"
#include "core/parallel.h"
#include "core/text.h"

namespace surrogate::hrti {

namespace {
constexpr const char* kStep = "highlight detection";
// Below this peak (of full scale) there is no highlight, only the sphere's dark body.
constexpr double kMinimumPeak = 0.05;
// The measures read the disc within this fraction of the radius (see detectHighlight).
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
    h.reason = "nothing stands out of the sphere's body (its brightest value is " + percent(h.peak) +
               " of full scale): the light was behind the sphere or did not fire";
    return;
  }
  const double contrast = score(m.contrast, L::kGoodContrast, L::kMinContrast);
  const double spread = score(m.spread, L::kGoodSpread, L::kMaxSpread);
  const double shape = std::min({score(m.share, L::kGoodShare, L::kMinShare),
                                 score(m.fill, L::kGoodFill, L::kMinFill),
                                 score(m.elongation, L::kGoodElongation, L::kMinElongation)});
  h.confidence = std::min({contrast, spread, shape, secondCandidate ? L::kMultipleCap : 1.0});
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
    h.reason = percent(m.spread) + " of the sphere is at least halfway up to its brightest value "
               "(a highlight covers under " + percent(L::kMaxSpread) + ")";
  } else if (m.share < L::kMinShare) {
    h.flag = HighlightFlag::NotCompact;
    h.reason = "the brightest pixels are scattered over the sphere: the spot nearest the centre holds " +
               percent(m.share) + " of them (a highlight holds at least " + percent(L::kMinShare) + ")";
  } else if (m.fill < L::kMinFill || m.elongation < L::kMinElongation) {
    h.flag = HighlightFlag::NotCompact;
    h.reason = "the brightest spot is not a compact peak but a ring or a streak (fill " + twoDecimals(m.fill) +
               ", a highlight has at least " + twoDecimals(L::kMinFill) + "; roundness " +
               twoDecimals(m.elongation) + ", at least " + twoDecimals(L::kMinElongation) + ")";
  } else {
    h.flag = secondCandidate ? HighlightFlag::Multiple : HighlightFlag::Ok;
    if (secondCandidate)
      h.reason = "another spot on the sphere is nearly as bright; the one nearest the centre was used";
    return;
  }
  h.confidence = 0;
}

Highlight detectHighlight(const Image& crop, int cropX0, int cropY0, const DetectedSphere& s,
                          const HighlightOptions& o) {
  Highlight h;
  h.x = s.cx;
  h.y = s.cy;
  const double inner = s.r - o.rimPixels;
  // Where a highlight can be: a light in front of the object puts it within sin(45 deg) of the
  // radius; the rim beyond reflects the surroundings (a bright backdrop at grazing angles).
  const double measured = std::min(inner, kMeasuredRadius * s.r);
  const int x0 = std::max(0, static_cast<int>(std::floor(s.cx - inner)) - cropX0);
  const int y0 = std::max(0, static_cast<int>(std::floor(s.cy - inner)) - cropY0);
  const int x1 = std::min(crop.width - 1, static_cast<int>(std::ceil(s.cx + inner)) - cropX0);
  const int y1 = std::min(crop.height - 1, static_cast<int>(std::ceil(s.cy + inner)) - cropY0);
  if (x1 <= x0 || y1 <= y0) {
    judgeHighlight(h, false);
    return h;
  }
  const int w = x1 - x0 + 1, hh = y1 - y0 + 1;
  cv::Mat values(hh, w, CV_32F, cv::Scalar(0));
  cv::Mat inside(hh, w, CV_8U, cv::Scalar(0));  // 1 inside the disc, 2 inside the measured disc
  std::vector<float> disc;                        // values of the measured disc
  double peak = 0;
  for (int y = 0; y < hh; ++y) {
    for (int x = 0; x < w; ++x) {
      const double fx = x + x0 + cropX0, fy = y + y0 + cropY0;
      const double d = std::hypot(fx - s.cx, fy - s.cy);
      if (d > inner) continue;
      const float v = crop.at(x + x0, y + y0) / 65535.0f;
      values.at<float>(y, x) = v;
      inside.at<std::uint8_t>(y, x) = d <= measured ? 2 : 1;
      if (d <= measured) disc.push_back(v);
      peak = std::max(peak, double(v));
    }
  }
  h.peak = peak;
  if (peak < kMinimumPeak || disc.empty()) {
    judgeHighlight(h, false);  // flag None
    return h;
  }
  // The sphere's body: the median of the measured disc (the highlight is a small part of it).
  std::nth_element(disc.begin(), disc.begin() + disc.size() / 2, disc.end());
  const double body = disc[disc.size() / 2];
  const float halfway = static_cast<float>((body + peak) / 2);
  int aboveHalfway = 0, saturated = 0;
  for (int y = 0; y < hh; ++y)
    for (int x = 0; x < w; ++x) {
      if (inside.at<std::uint8_t>(y, x) != 2) continue;
      const float v = values.at<float>(y, x);
      aboveHalfway += v >= halfway;
      saturated += v >= static_cast<float>(HighlightLimits::kSaturatedLevel);
    }
  h.measures.contrast = (peak - body) / peak;
  h.measures.spread = double(aboveHalfway) / disc.size();
  h.measures.saturated = double(saturated) / disc.size();

  cv::Mat mask = (values >= static_cast<float>(o.threshold * peak)) & (inside > 0);
  cv::Mat labels;
  const int count = cv::connectedComponents(mask, labels, 8, CV_32S);
  struct Component {
    double sum = 0, sx = 0, sy = 0, peak = 0;
    double px = 0, py = 0, pxx = 0, pyy = 0, pxy = 0;  // unweighted position moments
    int area = 0, measuredArea = 0;
  };
  std::vector<Component> comps(count);
  for (int y = 0; y < hh; ++y) {
    for (int x = 0; x < w; ++x) {
      const int l = labels.at<int>(y, x);
      if (l == 0) continue;
      const double v = values.at<float>(y, x);
      Component& c = comps[l];
      c.sum += v;
      c.sx += v * (x + x0 + cropX0);
      c.sy += v * (y + y0 + cropY0);
      c.peak = std::max(c.peak, v);
      c.area++;
      c.measuredArea += inside.at<std::uint8_t>(y, x) == 2;
      c.px += x;
      c.py += y;
      c.pxx += double(x) * x;
      c.pyy += double(y) * y;
      c.pxy += double(x) * y;
    }
  }
  int chosen = -1;
  double nearest = 1e300;
  for (int l = 1; l < count; ++l) {
    const double d = std::hypot(comps[l].sx / comps[l].sum - s.cx, comps[l].sy / comps[l].sum - s.cy);
    if (d < nearest) {
      nearest = d;
      chosen = l;
    }
  }
  if (chosen < 0) {
    judgeHighlight(h, false);
    return h;
  }
  const Component& c = comps[chosen];
  h.components = count - 1;
  h.x = c.sx / c.sum;
  h.y = c.sy / c.sum;
  h.flag = HighlightFlag::Ok;
  // The shape of the chosen component: covariance of its pixel positions, each pixel a unit
  // square (variance 1/12 along each axis).
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
  int bright = 0;
  for (int l = 1; l < count; ++l) bright += comps[l].measuredArea;
  h.measures.share = bright > 0 ? std::min(1.0, double(c.measuredArea) / bright) : 1.0;
  bool second = false;
  for (int l = 1; l < count; ++l)
    if (l != chosen && comps[l].area >= 3 && comps[l].peak >= 0.9 * c.peak) second = true;
  judgeHighlight(h, second);
  return h;
}

std::vector<std::vector<Highlight>> detectHighlights(const ImageStack& stack,
                                                     const std::vector<DetectedSphere>& spheres,
                                                     const HighlightOptions& o, int threads) {
  if (stack.channels() != 1) throw Error(ErrorKind::Internal, "", kStep, "needs a luminance stack");
  std::vector<std::vector<Highlight>> out(stack.size(), std::vector<Highlight>(spheres.size()));
  parallelFor(stack.size(), 1, effectiveThreads(threads), [&](std::size_t b, std::size_t e) {
    for (std::size_t i = b; i < e; ++i) {
      for (std::size_t k = 0; k < spheres.size(); ++k) {
        const DetectedSphere& s = spheres[k];
        // The sphere's square and two pixels around it: all detectHighlight reads (it clips
        // its disc to the frame, as it would to whole rows).
        const int y0 = std::clamp(static_cast<int>(std::floor(s.cy - s.r)) - 2, 0, stack.height());
        const int y1 = std::clamp(static_cast<int>(std::ceil(s.cy + s.r)) + 3, 0, stack.height());
        const int x0 = std::clamp(static_cast<int>(std::floor(s.cx - s.r)) - 2, 0, stack.width());
        const int x1 = std::clamp(static_cast<int>(std::ceil(s.cx + s.r)) + 3, 0, stack.width());
        if (y1 <= y0 || x1 <= x0) continue;
        Image window(x1 - x0, y1 - y0, 1);
        stack.readWindow(static_cast<int>(i), x0, y0, x1, y1, window.pixels.data());
        out[i][k] = detectHighlight(window, x0, y0, s, o);
      }
    }
  });
  return out;
}

}  // namespace surrogate::hrti
