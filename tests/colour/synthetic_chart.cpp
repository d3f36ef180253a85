// Synthetic ColorChecker pictures. See synthetic_chart.h.
//
// Drawn at 16 bits per channel in linear light (antialiased polygons with 8 fractional bits), so
// that exposure and light gradients act as they do on a sensor, then encoded as the scene asks.
#include "synthetic_chart.h"

#include <cmath>
#include <vector>

#include <opencv2/imgproc.hpp>

namespace surrogate::colour::test {

const std::array<std::array<int, 3>, 24> kDrawnSrgb = {{
    {115, 82, 68},   {194, 150, 130}, {98, 122, 157},  {87, 108, 67},   {133, 128, 177},
    {103, 189, 170}, {214, 126, 44},  {80, 91, 166},   {193, 90, 99},   {94, 60, 108},
    {157, 188, 64},  {224, 163, 46},  {56, 61, 150},   {70, 148, 73},   {175, 54, 60},
    {231, 199, 31},  {187, 86, 149},  {8, 133, 161},   {243, 243, 242}, {200, 200, 200},
    {160, 160, 160}, {122, 122, 121}, {85, 85, 85},    {52, 52, 52}}};

namespace {

double decode(double e) { return e <= 0.04045 ? e / 12.92 : std::pow((e + 0.055) / 1.055, 2.4); }
double encode(double l) {
  l = std::min(1.0, std::max(0.0, l));
  return l <= 0.0031308 ? 12.92 * l : 1.055 * std::pow(l, 1 / 2.4) - 0.055;
}

// Linear-light background: a blurred random texture with fine noise on top.
cv::Mat background(int width, int height, unsigned seed) {
  cv::RNG rng(seed);
  cv::Mat coarse(height, width, CV_32FC3), fine(height, width, CV_32FC3);
  rng.fill(coarse, cv::RNG::NORMAL, cv::Scalar::all(0.2), cv::Scalar::all(0.4));
  cv::GaussianBlur(coarse, coarse, cv::Size(0, 0), 4);
  rng.fill(fine, cv::RNG::NORMAL, cv::Scalar::all(0), cv::Scalar::all(0.01));
  return coarse + fine;
}

Image encodeImage(const cv::Mat& linear, bool sixteenBit, Transfer transfer) {
  Image im(linear.cols, linear.rows, 3);
  im.transfer = transfer;
  im.bitsPerSample = sixteenBit ? 16 : 8;
  for (int y = 0; y < linear.rows; ++y)
    for (int x = 0; x < linear.cols; ++x)
      for (int c = 0; c < 3; ++c) {
        double v = std::min(1.0, std::max(0.0, static_cast<double>(linear.at<cv::Vec3f>(y, x)[c])));
        if (transfer == Transfer::Srgb) v = encode(v);
        im.at(x, y, c) = sixteenBit ? static_cast<std::uint16_t>(std::lround(v * 65535))
                                    : static_cast<std::uint16_t>(std::lround(v * 255) * 257);
      }
  return im;
}

}  // namespace

DrawnChart drawChart(const ChartScene& s) {
  cv::Mat linear = background(s.width, s.height, s.seed);
  const double gap = s.gapFraction * s.pitch;
  const double w = 6 * s.pitch - gap, h = 4 * s.pitch - gap;
  // The chart's own frame (grid from (0,0) to (w,h)) to the image: turn about the centre, then
  // the right side shortened (keystone) by a homography.
  const double a = s.angle * M_PI / 180, ca = std::cos(a), sa = std::sin(a);
  auto place = [&](double x, double y) {
    const double k = 1 - s.keystone * x / w;  // height scale at x
    const double yk = h / 2 + (y - h / 2) * k;
    const double px = x - w / 2, py = yk - h / 2;
    return cv::Point2d(s.cx + ca * px - sa * py, s.cy + sa * px + ca * py);
  };
  // Only the four grid corners come from place(): everything is drawn through their homography.
  std::vector<cv::Point2f> own = {{0, 0}, {float(w), 0}, {float(w), float(h)}, {0, float(h)}};
  std::vector<cv::Point2f> img;
  DrawnChart out;
  for (int i = 0; i < 4; ++i) {
    const cv::Point2d p = place(own[i].x, own[i].y);
    img.emplace_back(float(p.x), float(p.y));
    out.corners[i] = {p.x, p.y};
  }
  const cv::Mat H = cv::getPerspectiveTransform(own, img);
  auto quad = [&](double x0, double y0, double x1, double y1, const cv::Scalar& colour) {
    std::vector<cv::Point2f> src = {{float(x0), float(y0)}, {float(x1), float(y0)},
                                    {float(x1), float(y1)}, {float(x0), float(y1)}};
    std::vector<cv::Point2f> dst;
    cv::perspectiveTransform(src, dst, H);
    std::vector<cv::Point> fixed;
    // OpenCV draws with pixel centres at integer coordinates, as the chart's corners are given.
    for (const auto& p : dst) fixed.emplace_back(cvRound(p.x * 256), cvRound(p.y * 256));
    cv::fillConvexPoly(linear, fixed, colour, cv::LINE_AA, 8);
  };
  const double m = 0.6 * s.pitch;
  quad(-m, -m, w + m, h + m, cv::Scalar::all(decode(30 / 255.0)));
  for (int k = 0; k < 24; ++k) {
    const double x0 = (k % 6) * s.pitch, y0 = (k / 6) * s.pitch, side = s.pitch - gap;
    cv::Scalar colour;
    for (int ch = 0; ch < 3; ++ch) colour[ch] = decode(kDrawnSrgb[k][ch] / 255.0) * s.exposure;
    quad(x0, y0, x0 + side, y0 + side, colour);
  }
  if (s.lightGradient != 0)  // more light to the right: 1 - g/2 at the chart's left edge
    for (int y = 0; y < linear.rows; ++y)
      for (int x = 0; x < linear.cols; ++x)
        linear.at<cv::Vec3f>(y, x) *= float(1 + s.lightGradient * (x - s.cx) / w);
  cv::Mat noise(linear.size(), CV_32FC3);
  cv::RNG rng(s.seed + 7);
  rng.fill(noise, cv::RNG::NORMAL, cv::Scalar::all(0), cv::Scalar::all(0.002));
  linear += noise;
  out.image = encodeImage(linear, s.sixteenBit, s.transfer);
  return out;
}

Image drawNoChart(int width, int height, bool rectangles, unsigned seed) {
  cv::Mat linear = background(width, height, seed);
  if (rectangles) {
    cv::RNG rng(seed + 3);
    for (int i = 0; i < 60; ++i) {
      const int x = rng.uniform(0, width - 40), y = rng.uniform(0, height - 40);
      const int side = rng.uniform(15, 60);
      cv::rectangle(linear, cv::Rect(x, y, side, side),
                    cv::Scalar(rng.uniform(0.0, 1.0), rng.uniform(0.0, 1.0), rng.uniform(0.0, 1.0)),
                    cv::FILLED);
    }
  }
  return encodeImage(linear, false, Transfer::Srgb);
}

}  // namespace surrogate::colour::test
