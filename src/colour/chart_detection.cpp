// Finding a ColorChecker Classic: OpenCV's mcc for a rough place, the patch colours for its
// orientation, the patch edges for the exact place. See chart_detection.h.
//
// mcc works on a display-referred 8-bit BGR copy (linear images are encoded with the sRGB curve
// first), reduced to at most ~1600 pixels across: beyond that it only gets slower. Its box can be
// 10-16 px off and its first corner is any of the four, so the four rotations are scored against
// the reference colours, then the grid is refined on the reduced copy and, for a reduced copy,
// again at full resolution.
#include "colour/chart_detection.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <vector>

#include <opencv2/imgproc.hpp>
#include <opencv2/mcc.hpp>

#include "colour/chart_grid.h"
#include "core/error.h"

namespace surrogate::colour {
namespace {

constexpr int kMaxSearchSide = 1600;

// Display-encoded value (0..255) of every 16-bit sample.
std::vector<float> encodedTable(Transfer transfer) {
  std::vector<float> t(65536);
  for (int v = 0; v < 65536; ++v)
    t[v] = static_cast<float>(
        255.0 * (transfer == Transfer::Linear ? srgbEncode(v / 65535.0) : v / 65535.0));
  return t;
}

// The image reduced by `factor` (block means of the encoded samples), 8-bit BGR.
cv::Mat reducedBgr(const Image& im, const std::vector<float>& enc, int factor) {
  const int w = im.width / factor, h = im.height / factor, n = im.channels;
  cv::Mat out(h, w, CV_8UC3);
  if (factor == 1) {
    // Each pixel's own samples: the byte of every 16-bit value looked up, the same rounding of
    // the same mean (a sum of one) as below, without a double sum per sample.
    std::vector<std::uint8_t> byte(enc.size());
    for (std::size_t v = 0; v < enc.size(); ++v) byte[v] = cv::saturate_cast<std::uint8_t>(static_cast<double>(enc[v]));
    for (int y = 0; y < h; ++y) {
      auto* row = out.ptr<std::uint8_t>(y);
      const std::uint16_t* in = im.pixels.data() + static_cast<std::size_t>(y) * w * n;
      for (int x = 0; x < w; ++x, in += n)
        for (int c = 0; c < 3; ++c) row[3 * x + 2 - c] = byte[in[n == 3 ? c : 0]];
    }
    return out;
  }
  for (int y = 0; y < h; ++y) {
    auto* row = out.ptr<std::uint8_t>(y);
    for (int x = 0; x < w; ++x) {
      double sum[3] = {0, 0, 0};
      for (int dy = 0; dy < factor; ++dy)
        for (int dx = 0; dx < factor; ++dx)
          for (int c = 0; c < 3; ++c)
            sum[c] += enc[im.at(x * factor + dx, y * factor + dy, n == 3 ? c : 0)];
      for (int c = 0; c < 3; ++c)
        row[3 * x + 2 - c] = cv::saturate_cast<std::uint8_t>(sum[c] / (factor * factor));
    }
  }
  return out;
}

// Mean of the encoded channels, full resolution, inside `roi`.
cv::Mat greyOf(const Image& im, const std::vector<float>& enc, const cv::Rect& roi) {
  cv::Mat g(roi.height, roi.width, CV_32F);
  for (int y = 0; y < roi.height; ++y)
    for (int x = 0; x < roi.width; ++x) {
      float s = 0;
      for (int c = 0; c < im.channels; ++c) s += enc[im.at(roi.x + x, roi.y + y, c)];
      g.at<float>(y, x) = s / im.channels;
    }
  return g;
}

cv::Mat greyOf(const cv::Mat& bgr) {
  cv::Mat g(bgr.rows, bgr.cols, CV_32F);
  for (int y = 0; y < bgr.rows; ++y)
    for (int x = 0; x < bgr.cols; ++x) {
      const auto& p = bgr.at<cv::Vec3b>(y, x);
      g.at<float>(y, x) = (p[0] + p[1] + p[2]) / 3.0f;
    }
  return g;
}

// How far the patch colours under these corners are from the reference chart's (per-channel
// gain fitted, residual relative to the signal): ~0.05 for the right rotation.
double orientationMisfit(const cv::Mat& bgr, const std::array<Point, 4>& corners,
                         const std::array<Rgb, kChartPatches>& reference) {
  const Homography h = homography(corners);
  std::array<Rgb, kChartPatches> seen{};
  for (int k = 0; k < kChartPatches; ++k) {
    const UnitRect r = centralRect(k, kDefaultGap, 0.2);
    int count = 0;
    for (int i = 0; i < 5; ++i)
      for (int j = 0; j < 5; ++j) {
        const Point p = h.map(r.u0 + (r.u1 - r.u0) * (i + 0.5) / 5,
                              r.v0 + (r.v1 - r.v0) * (j + 0.5) / 5);
        const int x = static_cast<int>(std::lround(p[0])), y = static_cast<int>(std::lround(p[1]));
        if (x < 0 || y < 0 || x >= bgr.cols || y >= bgr.rows) continue;
        const auto& v = bgr.at<cv::Vec3b>(y, x);
        for (int c = 0; c < 3; ++c) seen[k][c] += srgbDecode(v[2 - c] / 255.0);
        ++count;
      }
    if (count == 0) return std::numeric_limits<double>::infinity();
    for (double& c : seen[k]) c /= count;
  }
  double misfit = 0;
  for (int c = 0; c < 3; ++c) {
    double sr = 0, rr = 0, ss = 0;
    for (int k = 0; k < kChartPatches; ++k)
      sr += seen[k][c] * reference[k][c], rr += reference[k][c] * reference[k][c],
          ss += seen[k][c] * seen[k][c];
    const double gain = sr / rr;
    double e = 0;
    for (int k = 0; k < kChartPatches; ++k) e += std::pow(seen[k][c] - gain * reference[k][c], 2);
    misfit += ss > 0 ? e / ss : 1;
  }
  return misfit / 3;
}

double signedArea(const std::array<Point, 4>& c) {
  double a = 0;
  for (int i = 0; i < 4; ++i)
    a += c[i][0] * c[(i + 1) % 4][1] - c[(i + 1) % 4][0] * c[i][1];
  return a / 2;  // > 0: clockwise on the screen (y down)
}

cv::Rect around(const Grid& g, int width, int height) {
  double x0 = 1e300, y0 = 1e300, x1 = -1e300, y1 = -1e300;
  for (const Point& p : g.corners)
    x0 = std::min(x0, p[0]), y0 = std::min(y0, p[1]), x1 = std::max(x1, p[0]),
    y1 = std::max(y1, p[1]);
  const double margin = std::max(x1 - x0, y1 - y0) / 6 + 4;
  const cv::Rect r(cv::Point(static_cast<int>(std::floor(x0 - margin)),
                             static_cast<int>(std::floor(y0 - margin))),
                   cv::Point(static_cast<int>(std::ceil(x1 + margin)),
                             static_cast<int>(std::ceil(y1 + margin))));
  return r & cv::Rect(0, 0, width, height);
}

Grid refineInside(const cv::Mat& grey, Grid g, const std::vector<double>& sigmas) {
  const cv::Rect roi = around(g, grey.cols, grey.rows);
  if (roi.width < 8 || roi.height < 8) return g;
  for (Point& p : g.corners) p[0] -= roi.x, p[1] -= roi.y;
  g = refineGrid(grey(roi), g, sigmas);
  for (Point& p : g.corners) p[0] += roi.x, p[1] += roi.y;
  return g;
}

// The smaller side mcc enlarges a picture to before searching it (see findChart).
constexpr int kMccMinImageSize = 400;

}  // namespace

std::optional<ChartPlace> findChart(const Image& image) {
  if (image.empty() || (image.channels != 3 && image.channels != 1)) return std::nullopt;
  const std::vector<float> enc = encodedTable(image.transfer);
  const int factor = std::max(1, (std::max(image.width, image.height) + kMaxSearchSide - 1) /
                                     kMaxSearchSide);
  const cv::Mat bgr = reducedBgr(image, enc, factor);

  cv::Ptr<cv::mcc::CCheckerDetector> detector = cv::mcc::CCheckerDetector::create();
  // mcc enlarges every picture whose smaller side is under minImageSize (1000 by default)
  // before its search, and its search holds ~45 bytes a pixel: 70 MB for a 200x150 frame,
  // which a batch job of 64 MB cannot spare. 400 keeps a small frame small; a chart found at
  // 1200x800 is found in the same place (measured on the generated and real charts).
  const cv::Ptr<cv::mcc::DetectorParameters> params = cv::mcc::DetectorParameters::create();
  params->minImageSize = kMccMinImageSize;
  if (!detector->process(bgr, cv::mcc::MCC24, 1, false, params)) return std::nullopt;
  const auto found = detector->getListColorChecker();
  if (found.empty()) return std::nullopt;
  const std::vector<cv::Point2f> box = found.front()->getBox();
  if (box.size() != 4) return std::nullopt;
  std::array<Point, 4> b;
  for (int i = 0; i < 4; ++i) b[i] = {box[i].x, box[i].y};
  if (signedArea(b) < 0) std::swap(b[1], b[3]);

  const std::array<Rgb, kChartPatches> reference =
      referenceLinearSrgb(chartReference(kDefaultChartReference));
  double bestMisfit = std::numeric_limits<double>::infinity();
  Grid grid;
  for (int turn = 0; turn < 4; ++turn) {
    std::array<Point, 4> c;
    for (int i = 0; i < 4; ++i) c[i] = b[(turn + i) % 4];
    const double misfit = orientationMisfit(bgr, c, reference);
    if (misfit < bestMisfit) bestMisfit = misfit, grid.corners = c;
  }
  if (!(bestMisfit < kMaxOrientationMisfit)) return std::nullopt;

  const double pitch = patchSideOf(grid) / (1 - grid.gap);
  grid = refineInside(greyOf(bgr), grid,
                      {std::max(1.5, 0.1 * pitch), std::max(1.0, 0.04 * pitch), 0.7});
  if (factor > 1) {
    for (Point& p : grid.corners)
      p[0] = (p[0] + 0.5) * factor - 0.5, p[1] = (p[1] + 0.5) * factor - 0.5;
    const cv::Rect roi = around(grid, image.width, image.height);
    Grid local = grid;
    for (Point& p : local.corners) p[0] -= roi.x, p[1] -= roi.y;
    local = refineGrid(greyOf(image, enc, roi), local, {0.75 * factor, 1.2, 0.7});
    for (Point& p : local.corners) p[0] += roi.x, p[1] += roi.y;
    grid = local;
  }
  ChartPlace place;
  place.corners = grid.corners;
  place.method = "found";
  place.patchSide = patchSideOf(grid);
  return place;
}

ChartPlace chartFromCorners(const std::array<Point, 4>& corners, const std::string& origin) {
  const char* what =
      "give the four corners of the chart's patch grid as X1,Y1,X2,Y2,X3,Y3,X4,Y4 in image "
      "pixels, in this order: the outer corner of dark skin, of bluish green, of black, of white "
      "(clockwise as the chart is seen in the image)";
  for (const Point& p : corners)
    if (!std::isfinite(p[0]) || !std::isfinite(p[1]))
      throw Error(ErrorKind::Usage, origin, "colour chart",
                  std::string("a chart corner is not a number: ") + what);
  for (int i = 0; i < 4; ++i) {
    const Point &a = corners[i], &b = corners[(i + 1) % 4], &c = corners[(i + 2) % 4];
    const double cross = (b[0] - a[0]) * (c[1] - b[1]) - (b[1] - a[1]) * (c[0] - b[0]);
    if (std::hypot(b[0] - a[0], b[1] - a[1]) < 1)
      throw Error(ErrorKind::Usage, origin, "colour chart",
                  "two chart corners are at the same place: " + std::string(what));
    if (cross <= 0)
      throw Error(ErrorKind::Usage, origin, "colour chart",
                  std::string("the chart corners do not make a convex quadrilateral in clockwise "
                              "order (corner ") +
                      std::to_string((i + 1) % 4 + 1) + " turns the wrong way): " + what);
  }
  ChartPlace place;
  place.corners = corners;
  place.method = "given";
  place.patchSide = patchSideOf({corners, kDefaultGap});
  return place;
}

std::array<PatchRegion, kChartPatches> patchRegions(const ChartPlace& place) {
  const double gap = gapFromPatchSide(place.corners, place.patchSide);
  const Homography h = homography(place.corners);
  std::array<PatchRegion, kChartPatches> regions;
  for (int k = 0; k < kChartPatches; ++k) {
    const UnitRect r = centralRect(k, gap, kCentralHalf);
    regions[k].corners = {h.map(r.u0, r.v0), h.map(r.u1, r.v0), h.map(r.u1, r.v1),
                          h.map(r.u0, r.v1)};
  }
  return regions;
}

}  // namespace surrogate::colour
