// The difference picture of the audit: prior minus photograph on Rec. 709 luminance, amplified to
// a full scale chosen from the data and shown on a diverging colour scale, with its legend drawn
// into the picture (docs/hrti-math.md, "Difference image").
#include <algorithm>
#include <cmath>
#include <opencv2/imgproc.hpp>

#include "audit/audit.h"
#include "core/error.h"
#include "core/text.h"

namespace surrogate::audit {
namespace {

// ColorBrewer RdBu, 11 classes, from the blue end (prior darker) to the red end (prior
// brighter); the middle class is the neutral colour of no difference.
constexpr std::uint8_t kStops[11][3] = {
    {5, 48, 97},    {33, 102, 172}, {67, 147, 195}, {146, 197, 222}, {209, 229, 240}, {247, 247, 247},
    {253, 219, 199}, {244, 165, 130}, {214, 96, 77},  {178, 24, 43},   {103, 0, 31}};

// The round numbers a full scale is rounded up to (8-bit levels); 255 is the whole range.
constexpr double kRoundScales[] = {4, 5, 6, 8, 10, 12, 16, 20, 25, 32, 40, 50, 64, 80, 100, 128, 160, 200, 255};

// The share of the differences' magnitudes at or below the full scale.
constexpr double kScaleQuantile = 0.99;

// The legend's geometry, in units of `u` pixels (u grows with the picture's width so that the
// legend stays legible on a picture of 6000 pixels).
constexpr int kMinPictureWidth = 560;  // room for the caption of a typical file name and light
constexpr int kUnitWidth = 700;        // one more unit of size per this many pixels of width
constexpr int kLegendHeight = 76;      // the band below the map
constexpr int kRampWidth = 512, kRampTop = 10, kRampHeight = 16, kMargin = 20;
constexpr int kTicksBaseline = 44, kCaptionBaseline = 66;
constexpr double kFontScale = 0.45;
const cv::Scalar kInk(32, 32, 32), kPaper(255, 255, 255), kBeside(160, 160, 160);

std::uint8_t mix(std::uint8_t a, std::uint8_t b, double f) {
  // Round half away from zero on non-negative values: floor(v + 0.5).
  return static_cast<std::uint8_t>(std::floor(a + f * (static_cast<double>(b) - a) + 0.5));
}

int textWidth(const std::string& text, double scale, int thickness) {
  int baseline = 0;
  return cv::getTextSize(text, cv::FONT_HERSHEY_SIMPLEX, scale, thickness, &baseline).width;
}

void text(cv::Mat& m, const std::string& t, int x, int y, double scale, int thickness) {
  cv::putText(m, t, cv::Point(x, y), cv::FONT_HERSHEY_SIMPLEX, scale, kInk, thickness, cv::LINE_AA);
}

std::string signedLevels(double v) {
  return (v > 0 ? "+" : v < 0 ? "-" : "") + formatNumber(std::abs(v));
}

// The legend below the map, whose top row is `top`: the ramp from -scale to +scale, its ends
// and middle, and the caption (made smaller until it fits the width).
void drawLegend(cv::Mat& m, int top, double scale, const std::string& caption) {
  const int u = std::max(1, m.cols / kUnitWidth);
  const int x0 = kMargin * u, rampWidth = std::min(kRampWidth * u, m.cols - 2 * kMargin * u);
  const int y0 = top + kRampTop * u, y1 = y0 + kRampHeight * u;
  for (int x = 0; x < rampWidth; ++x) {
    const double levels = (2.0 * (x + 0.5) / rampWidth - 1.0) * scale;
    const auto c = differenceColour(levels, scale);
    cv::rectangle(m, cv::Point(x0 + x, y0), cv::Point(x0 + x, y1 - 1), cv::Scalar(c[0], c[1], c[2]), cv::FILLED);
  }
  cv::rectangle(m, cv::Point(x0 - 1, y0 - 1), cv::Point(x0 + rampWidth, y1), kInk, 1);
  const int mid = x0 + rampWidth / 2;
  cv::line(m, cv::Point(mid, y1), cv::Point(mid, y1 + 4 * u), kInk, u);
  const double font = kFontScale * u;
  const std::string low = signedLevels(-scale) + " prior darker", high = signedLevels(scale) + " levels, prior brighter";
  const int baseline = top + kTicksBaseline * u;
  text(m, low, x0, baseline, font, u);
  text(m, "0", mid - textWidth("0", font, u) / 2, baseline, font, u);
  text(m, high, x0 + rampWidth - textWidth(high, font, u), baseline, font, u);
  double captionFont = font;
  while (captionFont > 0.2 && textWidth(caption, captionFont, u) > m.cols - 2 * kMargin * u) captionFont *= 0.9;
  text(m, caption, x0, top + kCaptionBaseline * u, captionFont, u);
}

}  // namespace

std::array<std::uint8_t, 3> differenceColour(double levels, double fullScale) {
  const double f = fullScale > 0 && std::isfinite(levels) ? std::clamp(levels / fullScale, -1.0, 1.0) : 0.0;
  const double at = (f + 1.0) * 5.0;  // 0 .. 10 along the stops
  const int i = std::min(9, static_cast<int>(at));
  const double w = at - i;
  return {mix(kStops[i][0], kStops[i + 1][0], w), mix(kStops[i][1], kStops[i + 1][1], w),
          mix(kStops[i][2], kStops[i + 1][2], w)};
}

double differenceScale(const std::vector<std::int32_t>& differences) {
  if (differences.empty()) return kRoundScales[0];
  // Nearest rank on the integer magnitudes, counted: exact and independent of any order.
  std::vector<std::size_t> count(65536, 0);
  for (std::int32_t d : differences) ++count[std::min<std::int64_t>(65535, std::abs(static_cast<std::int64_t>(d)))];
  const auto rank = static_cast<std::size_t>(std::ceil(kScaleQuantile * static_cast<double>(differences.size())));
  std::size_t seen = 0, magnitude = 0;
  for (; magnitude < count.size(); ++magnitude) {
    seen += count[magnitude];
    if (seen >= std::max<std::size_t>(1, rank)) break;
  }
  const double levels = static_cast<double>(magnitude) / 257.0;
  for (double s : kRoundScales)
    if (s >= levels) return s;
  return kRoundScales[std::size(kRoundScales) - 1];
}

DifferencePicture differencePicture(const Image& prior, const Image& photograph, const std::string& caption) {
  if (prior.width != photograph.width || prior.height != photograph.height || prior.empty() || photograph.empty())
    throw Error(ErrorKind::Internal, "", "audit", "difference of two images of different sizes");
  const Image a = luminance(prior), b = luminance(photograph);
  std::vector<std::int32_t> d(a.pixels.size());
  for (std::size_t p = 0; p < d.size(); ++p) d[p] = static_cast<std::int32_t>(a.pixels[p]) - b.pixels[p];
  DifferencePicture out;
  out.fullScale = differenceScale(d);

  const int w = a.width, h = a.height;
  const int width = std::max(w, kMinPictureWidth);
  const int u = std::max(1, width / kUnitWidth);
  cv::Mat m(h + kLegendHeight * u, width, CV_8UC3, kPaper);  // channels in RGB order throughout
  if (width > w) m(cv::Rect(w, 0, width - w, h)).setTo(kBeside);
  for (int y = 0; y < h; ++y) {
    auto* row = m.ptr<cv::Vec3b>(y);
    for (int x = 0; x < w; ++x) {
      const auto c = differenceColour(d[static_cast<std::size_t>(y) * w + x] / 257.0, out.fullScale);
      row[x] = cv::Vec3b(c[0], c[1], c[2]);
    }
  }
  cv::line(m, cv::Point(0, h), cv::Point(width - 1, h), kInk, 1);
  drawLegend(m, h, out.fullScale, caption);

  Image& pic = out.picture;
  pic = Image(width, m.rows, 3);
  pic.bitsPerSample = 8;
  for (int y = 0; y < m.rows; ++y) {
    const auto* row = m.ptr<cv::Vec3b>(y);
    for (int x = 0; x < width; ++x)
      for (int c = 0; c < 3; ++c) pic.at(x, y, c) = static_cast<std::uint16_t>(row[x][c] * 257);
  }
  return out;
}

}  // namespace surrogate::audit
