#include "hrti/highlight_detection.h"

#include <opencv2/core.hpp>
#include <opencv2/imgproc.hpp>

#include <algorithm>
#include <cmath>
#include <sstream>

#include "core/error.h"
#include "core/parallel.h"

namespace surrogate::hrti {

namespace {
constexpr const char* kStep = "highlight detection";
// Below this peak (of full scale) there is no highlight, only the sphere's dark body.
constexpr double kMinimumPeak = 0.05;
}  // namespace

std::vector<std::pair<std::string, std::string>> HighlightOptions::toParameters() const {
  std::ostringstream t;
  t.precision(17);
  t << threshold;
  return {{"threshold", t.str()}, {"rimPixels", std::to_string(rimPixels)}};
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

Highlight detectHighlight(const Image& crop, int cropX0, int cropY0, const DetectedSphere& s,
                          const HighlightOptions& o) {
  Highlight h;
  h.x = s.cx;
  h.y = s.cy;
  const double inner = s.r - o.rimPixels;
  const int x0 = std::max(0, static_cast<int>(std::floor(s.cx - inner)) - cropX0);
  const int y0 = std::max(0, static_cast<int>(std::floor(s.cy - inner)) - cropY0);
  const int x1 = std::min(crop.width - 1, static_cast<int>(std::ceil(s.cx + inner)) - cropX0);
  const int y1 = std::min(crop.height - 1, static_cast<int>(std::ceil(s.cy + inner)) - cropY0);
  if (x1 <= x0 || y1 <= y0) return h;
  const int w = x1 - x0 + 1, hh = y1 - y0 + 1;
  cv::Mat values(hh, w, CV_32F, cv::Scalar(0));
  cv::Mat inside(hh, w, CV_8U, cv::Scalar(0));
  double peak = 0;
  for (int y = 0; y < hh; ++y) {
    for (int x = 0; x < w; ++x) {
      const double fx = x + x0 + cropX0, fy = y + y0 + cropY0;
      if (std::hypot(fx - s.cx, fy - s.cy) > inner) continue;
      const float v = crop.at(x + x0, y + y0) / 65535.0f;
      values.at<float>(y, x) = v;
      inside.at<std::uint8_t>(y, x) = 1;
      peak = std::max(peak, double(v));
    }
  }
  h.peak = peak;
  if (peak < kMinimumPeak) return h;  // flag None
  cv::Mat mask = (values >= static_cast<float>(o.threshold * peak)) & inside;
  cv::Mat labels;
  const int count = cv::connectedComponents(mask, labels, 8, CV_32S);
  struct Component {
    double sum = 0, sx = 0, sy = 0, peak = 0;
    int area = 0;
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
  if (chosen < 0) return h;
  h.components = count - 1;
  h.x = comps[chosen].sx / comps[chosen].sum;
  h.y = comps[chosen].sy / comps[chosen].sum;
  h.flag = HighlightFlag::Ok;
  for (int l = 1; l < count; ++l)
    if (l != chosen && comps[l].area >= 3 && comps[l].peak >= 0.9 * comps[chosen].peak) h.flag = HighlightFlag::Multiple;
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
        const int y0 = std::clamp(static_cast<int>(std::floor(s.cy - s.r)) - 2, 0, stack.height());
        const int y1 = std::clamp(static_cast<int>(std::ceil(s.cy + s.r)) + 3, 0, stack.height());
        if (y1 <= y0) continue;
        Image rows(stack.width(), y1 - y0, 1);
        stack.readRows(static_cast<int>(i), y0, y1, rows.pixels.data());
        out[i][k] = detectHighlight(rows, 0, y0, s, o);
      }
    }
  });
  return out;
}

}  // namespace surrogate::hrti
