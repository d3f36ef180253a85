#include "hrti/drawing.h"

#include <opencv2/core.hpp>
#include <opencv2/imgproc.hpp>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <optional>
#include <string>

#include "core/error.h"

namespace surrogate::hrti {

namespace {

constexpr int kShift = 4;  // sub-pixel drawing: coordinates in 1/16 pixel
constexpr double kUnit = 1 << kShift;
// The highlight labels' font scale on the 600 px overview: about 13 px high, readable when the
// report shows the picture at half size.
constexpr double kLabelScale = 0.55;
// The highlight marks' radius on the overview, in pixels.
constexpr int kMarkRadius = 4;

cv::Mat greyToBgr8(const Image& grey) {
  cv::Mat m(grey.height, grey.width, CV_8U);
  for (int y = 0; y < grey.height; ++y)
    for (int x = 0; x < grey.width; ++x) m.at<std::uint8_t>(y, x) = static_cast<std::uint8_t>((grey.at(x, y) + 128) / 257);
  cv::Mat bgr;
  cv::cvtColor(m, bgr, cv::COLOR_GRAY2BGR);
  return bgr;
}

Image toImage(const cv::Mat& bgr) {
  Image out(bgr.cols, bgr.rows, 3);
  out.bitsPerSample = 8;
  out.transfer = Transfer::Srgb;
  for (int y = 0; y < bgr.rows; ++y)
    for (int x = 0; x < bgr.cols; ++x) {
      const cv::Vec3b p = bgr.at<cv::Vec3b>(y, x);
      for (int c = 0; c < 3; ++c) out.at(x, y, c) = static_cast<std::uint16_t>(p[2 - c] * 257);
    }
  return out;
}

// The drawings need a circle with a finite centre and a radius above 0 that overlaps the image;
// the stages refuse any other circle first (stages/frame_checks.h), this keeps a bad one from
// ever reaching an OpenCV assertion.
void checkDrawable(const DetectedSphere& s, int width, int height) {
  const bool finite = std::isfinite(s.cx) && std::isfinite(s.cy) && std::isfinite(s.r);
  if (!finite || !(s.r > 0) || s.cx + s.r < 0 || s.cy + s.r < 0 || s.cx - s.r > width - 1 ||
      s.cy - s.r > height - 1 || s.r > 1e6)
    throw Error(ErrorKind::Input, "", "sphere drawing",
                "a sphere's circle (" + std::to_string(s.cx) + ", " + std::to_string(s.cy) + ", " +
                    std::to_string(s.r) + ") is not a circle in the " + std::to_string(width) + "x" +
                    std::to_string(height) + " image; give the sphere's circle again (--sphere CX,CY,R)");
}

// Where a label's baseline starts so that the whole text lies inside the picture (2 px in from
// each edge), as near as possible to `wanted`: a label is never cut at the frame's edge.
cv::Point labelOrigin(const cv::Mat& picture, const std::string& text, double scale, int thickness, cv::Point wanted) {
  int baseline = 0;
  const cv::Size size = cv::getTextSize(text, cv::FONT_HERSHEY_SIMPLEX, scale, thickness, &baseline);
  const int x = std::clamp(wanted.x, 2, std::max(2, picture.cols - size.width - 2));
  const int y = std::clamp(wanted.y, size.height + 2, std::max(size.height + 2, picture.rows - baseline - 2));
  return {x, y};
}

// Text with a dark outline, readable on the bright and the dark parts of a sphere.
void outlinedText(cv::Mat& picture, const std::string& text, cv::Point at, double scale, int thickness,
                  const cv::Scalar& colour) {
  cv::putText(picture, text, at, cv::FONT_HERSHEY_SIMPLEX, scale, cv::Scalar(0, 0, 0), thickness + 2, cv::LINE_AA);
  cv::putText(picture, text, at, cv::FONT_HERSHEY_SIMPLEX, scale, colour, thickness, cv::LINE_AA);
}

// The box a label drawn at `origin` (its baseline's left end) covers, its outline included.
Rect textBox(cv::Point origin, cv::Size text, int baseline) {
  return {origin.x - 1, origin.y - text.height - 2, text.width + 2, text.height + baseline + 3};
}

bool overlaps(const Rect& a, const Rect& b) {
  return a.x < b.x + b.w && b.x < a.x + a.w && a.y < b.y + b.h && b.y < a.y + a.h;
}

cv::Point sub(double x, double y) { return {static_cast<int>(std::lround(x * kUnit)), static_cast<int>(std::lround(y * kUnit))}; }

}  // namespace

Image drawSphereOverlay(const Image& median, const std::vector<DetectedSphere>& spheres, int factor) {
  cv::Mat bgr = greyToBgr8(median);
  const int thickness = std::max(1, median.width / 600);
  for (std::size_t k = 0; k < spheres.size(); ++k) {
    const DetectedSphere& full = spheres[k];
    // A reduced pixel is the mean of factor x factor pixels: its centre is their centre.
    const DetectedSphere s{(full.cx + 0.5) / factor - 0.5, (full.cy + 0.5) / factor - 0.5, full.r / factor,
                           full.confidence, full.evidence, full.byHand};
    checkDrawable(s, median.width, median.height);
    cv::circle(bgr, sub(s.cx, s.cy), static_cast<int>(std::lround(s.r * kUnit)), cv::Scalar(0, 220, 0), thickness, cv::LINE_AA, kShift);
    const double arm = std::max(4.0, s.r / 8);
    cv::line(bgr, sub(s.cx - arm, s.cy), sub(s.cx + arm, s.cy), cv::Scalar(0, 220, 0), thickness, cv::LINE_AA, kShift);
    cv::line(bgr, sub(s.cx, s.cy - arm), sub(s.cx, s.cy + arm), cv::Scalar(0, 220, 0), thickness, cv::LINE_AA, kShift);
    char label[64];
    // Spheres are numbered from 1, as in the file names (highlights-sphere1.png) and the report.
    // One given by hand has no confidence of its own: it says so.
    if (full.byHand) std::snprintf(label, sizeof label, "sphere %zu  r=%.1f  by hand", k + 1, full.r);
    else std::snprintf(label, sizeof label, "sphere %zu  r=%.1f  conf %.2f", k + 1, full.r, s.confidence);
    const double scale = std::max(0.4, median.width / 2000.0);
    const int ty = static_cast<int>(s.cy + s.r + 20 * scale) < median.height ? static_cast<int>(s.cy + s.r + 20 * scale)
                                                                             : static_cast<int>(s.cy - s.r - 6);
    const cv::Point at = labelOrigin(bgr, label, scale, thickness, cv::Point(static_cast<int>(s.cx - s.r), ty));
    outlinedText(bgr, label, at, scale, thickness, cv::Scalar(0, 220, 0));
  }
  return toImage(bgr);
}

std::vector<std::optional<Rect>> placeLabels(const std::vector<std::pair<int, int>>& marks,
                                             const std::vector<std::pair<int, int>>& sizes, int width, int height,
                                             int markRadius) {
  std::vector<Rect> taken;  // every mark, then each label placed
  for (const auto& [mx, my] : marks) taken.push_back({mx - markRadius, my - markRadius, 2 * markRadius + 1, 2 * markRadius + 1});
  std::vector<std::optional<Rect>> out;
  for (std::size_t i = 0; i < marks.size(); ++i) {
    const auto [mx, my] = marks[i];
    const auto [w, h] = sizes[i];
    // The first place: right of the mark and above it, as the labels were always drawn.
    const int x0 = mx + markRadius + 3, y0 = my - h + 1;
    const int stepX = 8, stepY = h + 1;
    const int rings = std::max(width / stepX, height / stepY) + 1;
    const auto fits = [&](const Rect& r) {
      if (r.x < 0 || r.y < 0 || r.x + r.w > width || r.y + r.h > height) return false;
      for (const Rect& t : taken)
        if (overlaps(r, t)) return false;
      return true;
    };
    std::optional<Rect> placed;
    // The first ring: the four places beside the mark (right or left, above or below).
    for (const Rect& r : {Rect{x0, y0, w, h}, Rect{x0, my, w, h}, Rect{mx - markRadius - 3 - w, y0, w, h},
                          Rect{mx - markRadius - 3 - w, my, w, h}})
      if (!placed && fits(r)) placed = r;
    // Then rings around the first place, nearest first, top to bottom and left to right.
    for (int k = 1; !placed && k <= rings; ++k)
      for (int j = -k; j <= k && !placed; ++j)
        for (int i = -k; i <= k && !placed; i += (j == -k || j == k) ? 1 : 2 * k) {
          const Rect r{x0 + i * stepX, y0 + j * stepY, w, h};
          if (fits(r)) placed = r;
        }
    if (placed) taken.push_back(*placed);
    out.push_back(placed);
  }
  return out;
}

Image drawHighlightOverview(const Image& median, const DetectedSphere& s, const std::vector<Highlight>& perImage,
                            const std::vector<std::string>& labels) {
  const MedianCrop crop = [&](const Rect& r) {
    Image out(r.w, r.h, 1);
    out.transfer = median.transfer;
    for (int y = 0; y < r.h; ++y)
      for (int x = 0; x < r.w; ++x) out.at(x, y) = median.at(r.x + x, r.y + y);
    return out;
  };
  return drawHighlightOverview(median.width, median.height, crop, s, perImage, labels);
}

Image drawHighlightOverview(int width, int height, const MedianCrop& medianCrop, const DetectedSphere& s,
                            const std::vector<Highlight>& perImage, const std::vector<std::string>& labels) {
  checkDrawable(s, width, height);
  const double margin = s.r * 0.15;
  const int x0 = std::max(0, static_cast<int>(std::floor(s.cx - s.r - margin)));
  const int y0 = std::max(0, static_cast<int>(std::floor(s.cy - s.r - margin)));
  const int x1 = std::min(width, static_cast<int>(std::ceil(s.cx + s.r + margin)) + 1);
  const int y1 = std::min(height, static_cast<int>(std::ceil(s.cy + s.r + margin)) + 1);
  cv::Mat crop = greyToBgr8(medianCrop({x0, y0, x1 - x0, y1 - y0}));
  // Brighten the dark sphere so the marks read against it.
  crop.convertTo(crop, -1, 1.0, 40);
  const double zoom = 600.0 / std::max(crop.cols, crop.rows);
  cv::Mat big;
  cv::resize(crop, big, cv::Size(), zoom, zoom, cv::INTER_LINEAR);
  auto map = [&](double x, double y) { return sub((x - x0 + 0.5) * zoom - 0.5, (y - y0 + 0.5) * zoom - 0.5); };
  cv::circle(big, map(s.cx, s.cy), static_cast<int>(std::lround(s.r * zoom * kUnit)), cv::Scalar(0, 200, 0), 2, cv::LINE_AA, kShift);
  // The marks first, then their labels where placeLabels puts them: clustered highlights
  // (nearby lights) would otherwise write their labels over each other.
  std::vector<std::size_t> shown;
  std::vector<std::pair<int, int>> marks, sizes;
  std::vector<int> baselines;
  for (std::size_t i = 0; i < perImage.size(); ++i) {
    const Highlight& h = perImage[i];
    if (!isUsable(h.flag)) continue;  // refused: its position means nothing
    const cv::Scalar colour = h.flag == HighlightFlag::Ok ? cv::Scalar(40, 40, 255) : cv::Scalar(0, 230, 255);
    cv::circle(big, map(h.x, h.y), static_cast<int>(4 * kUnit), colour, -1, cv::LINE_AA, kShift);
    const std::string label = i < labels.size() ? labels[i] : std::to_string(i + 1);
    int baseline = 0;
    const cv::Size text = cv::getTextSize(label, cv::FONT_HERSHEY_SIMPLEX, kLabelScale, 1, &baseline);
    const Rect box = textBox({0, 0}, text, baseline);
    const cv::Point mark = map(h.x, h.y);
    shown.push_back(i);
    marks.emplace_back(mark.x / static_cast<int>(kUnit), mark.y / static_cast<int>(kUnit));
    sizes.emplace_back(box.w, box.h);
    baselines.push_back(-box.y);  // from the box's top to the baseline
  }
  const std::vector<std::optional<Rect>> places = placeLabels(marks, sizes, big.cols, big.rows, kMarkRadius);
  for (std::size_t n = 0; n < shown.size(); ++n) {
    if (!places[n]) continue;  // no free place left in the picture: the mark stays unlabelled
    const Highlight& h = perImage[shown[n]];
    const cv::Scalar colour = h.flag == HighlightFlag::Ok ? cv::Scalar(40, 40, 255) : cv::Scalar(0, 230, 255);
    const Rect& r = *places[n];
    const auto [mx, my] = marks[n];
    // A label away from its mark is joined to it: a line from the mark to the box's nearest point.
    const int nx = std::clamp(mx, r.x, r.x + r.w - 1), ny = std::clamp(my, r.y, r.y + r.h - 1);
    if (std::hypot(nx - mx, ny - my) > kMarkRadius + 4)
      cv::line(big, {mx, my}, {nx, ny}, colour, 1, cv::LINE_AA);
    const std::string label = shown[n] < labels.size() ? labels[shown[n]] : std::to_string(shown[n] + 1);
    outlinedText(big, label, cv::Point(r.x + 1, r.y + baselines[n]), kLabelScale, 1, colour);
  }
  return toImage(big);
}

}  // namespace surrogate::hrti
