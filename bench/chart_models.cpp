// chart_models: does a root-polynomial correction do better than a 3x3 matrix on real charts?
// (issue 54). For each photograph in DIR/corners.txt (tests/data/colour-real): the chart's
// patches measured inside the hand-measured grid corners, both models fitted with the neutral
// patches 19..22 fixing the white point, and CIEDE2000 mean and max against each edition's
// reference: uncorrected (exposure-normalised only), fitted (the patches the model was fitted
// to) and leave-one-out (each patch corrected by the model fitted without it: what the model
// does on colours it has not seen). Then how far the automatic search (findChart) put the grid
// from the hand corners.
//
//   chart_models [DIR]        the photographs in DIR (tests/data/colour-real/SOURCE.md says
//                              where each comes from; they are not in the repository);
//                              corners.txt from DIR, else from tests/data/colour-real. A
//                              photograph not there is named and skipped.
//
// Measured: the mean in linear light of the pixels whose centres lie in the central 50 % square
// of each patch, found through this file's own homography from the four corners (not through
// src/colour's patchRegions, so a fault there does not hide itself). JPEG/PNG samples are
// decoded through the sRGB curve, camera raws (decodeImage: linear) used as they are. A patch
// with more than 1 % of its samples at full scale is counted as clipped and reported.
// Uncorrected: the linear RGB scaled by the one factor that gives patches 19..22 the mean Y of
// the reference's (as bench/chart_error.cpp), read as linear sRGB.
#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <optional>
#include <sstream>
#include <string>
#include <vector>

#include <opencv2/core.hpp>
#include <opencv2/imgproc.hpp>

#include "colour/chart_detection.h"
#include "colour/chart_reference.h"
#include "colour/colour_space.h"
#include "colour/correction_model.h"
#include "colour/delta_e.h"
#include "core/error.h"
#include "image/decode.h"

using namespace surrogate;
using namespace surrogate::colour;

namespace {

const std::vector<int> kNeutrals = {19, 20, 21, 22};
// The gap between patches as a fraction of a patch's side (Classic about 0.13, Passport about
// 0.2): only places each patch's centre inside the grid; the central 50 % square leaves a
// quarter of a side of margin, far more than this guess's error.
constexpr double kGapRatio = 0.15;

struct Entry {
  std::string file, edition;
  std::array<cv::Point2d, 4> corners;
};

std::vector<Entry> readCorners(const std::string& path) {
  std::ifstream in(path);
  if (!in)
    throw Error(ErrorKind::Input, path, "chart_models",
                "cannot read the corners file; give the folder holding corners.txt");
  std::vector<Entry> out;
  std::string line;
  while (std::getline(in, line)) {
    if (line.empty() || line[0] == '#') continue;
    std::istringstream s(line);
    Entry e;
    s >> e.file;
    for (auto& p : e.corners) s >> p.x >> p.y;
    s >> e.edition;
    if (!s)
      throw Error(ErrorKind::Input, path, "chart_models",
                  "a line is not 'file x1 y1 x2 y2 x3 y3 x4 y4 edition': " + line);
    out.push_back(e);
  }
  return out;
}

// Grid coordinates: (0,0) patch 0's outer corner, (6,0) patch 5's, (6,4) patch 23's, (0,4)
// patch 18's.
cv::Matx33d gridToImage(const std::array<cv::Point2d, 4>& c) {
  std::vector<cv::Point2f> g = {{0, 0}, {6, 0}, {6, 4}, {0, 4}}, q;
  for (const auto& p : c) q.emplace_back(static_cast<float>(p.x), static_cast<float>(p.y));
  return cv::Matx33d(cv::getPerspectiveTransform(g, q));
}

cv::Point2d apply(const cv::Matx33d& h, double u, double v) {
  const cv::Vec3d p = h * cv::Vec3d(u, v, 1);
  return {p[0] / p[2], p[1] / p[2]};
}

struct Measured {
  std::vector<Rgb> rgb;
  int clipped = 0;
};

Measured measure(const Image& im, const std::array<cv::Point2d, 4>& corners) {
  const cv::Matx33d h = gridToImage(corners), inv = h.inv();
  const double width = 6 + 5 * kGapRatio, height = 4 + 3 * kGapRatio;
  const double top = 65535.0 * 0.999;
  Measured m;
  for (int k = 0; k < kChartPatches; ++k) {
    const int col = k % kChartColumns, row = k / kChartColumns;
    // The patch's centre and half of its central 50 % square, in grid units.
    const double cu = (col * (1 + kGapRatio) + 0.5) * 6 / width;
    const double cv_ = (row * (1 + kGapRatio) + 0.5) * 4 / height;
    const double hu = 0.25 * 6 / width, hv = 0.25 * 4 / height;
    double x0 = 1e18, y0 = 1e18, x1 = -1e18, y1 = -1e18;
    for (int i = 0; i < 4; ++i) {
      const cv::Point2d p = apply(h, cu + (i & 1 ? hu : -hu), cv_ + (i & 2 ? hv : -hv));
      x0 = std::min(x0, p.x), y0 = std::min(y0, p.y), x1 = std::max(x1, p.x), y1 = std::max(y1, p.y);
    }
    std::array<double, 3> sum{0, 0, 0};
    int n = 0, atTop = 0;
    for (int y = std::max(0, int(std::ceil(y0))); y <= std::min(im.height - 1, int(y1)); ++y)
      for (int x = std::max(0, int(std::ceil(x0))); x <= std::min(im.width - 1, int(x1)); ++x) {
        const cv::Point2d g = apply(inv, x, y);
        if (std::abs(g.x - cu) > hu || std::abs(g.y - cv_) > hv) continue;
        bool full = false;
        for (int c = 0; c < 3; ++c) {
          const double v = im.at(x, y, im.channels == 3 ? c : 0);
          full = full || v >= top;
          sum[c] += im.transfer == Transfer::Srgb ? srgbDecode(v / 65535.0) : v / 65535.0;
        }
        atTop += full;
        ++n;
      }
    if (n == 0)
      throw Error(ErrorKind::Input, "corners", "chart_models",
                  "patch " + std::to_string(k) + " has no pixel inside the image");
    m.rgb.push_back({sum[0] / n, sum[1] / n, sum[2] / n});
    if (atTop > 0.01 * n) ++m.clipped;
  }
  return m;
}

double luminance(const Rgb& c) { return xyzD65FromLinearSrgb(c)[1]; }

struct Figures {
  double mean = 0, max = 0;
  int worst = 0;  // the patch of the max
};
Figures figures(const std::vector<Rgb>& rgb, const ChartReference& ref) {
  Figures f;
  for (int k = 0; k < kChartPatches; ++k) {
    const double d = deltaE2000(ref.lab[k], labD50FromLinearSrgb(rgb[k]));
    f.mean += d / kChartPatches;
    if (d > f.max) f.max = d, f.worst = k;
  }
  return f;
}

std::string cell(const Figures& f) {
  char b[40];
  std::snprintf(b, sizeof b, "%5.2f/%5.2f(%d)", f.mean, f.max, f.worst);
  return b;
}

void printFindChart(const Image& im, const Entry& e) {
  const std::optional<ChartPlace> place = findChart(im);
  if (!place) {
    std::printf("  findChart: not found\n");
    return;
  }
  double mean = 0, worst = 0;
  std::string each;
  for (int i = 0; i < 4; ++i) {
    const double d = std::hypot(place->corners[i][0] - e.corners[i].x,
                                place->corners[i][1] - e.corners[i].y);
    mean += d / 4;
    worst = std::max(worst, d);
    char b[48];
    std::snprintf(b, sizeof b, "%s%.1f at (%.1f, %.1f)", i ? ", " : "", d, place->corners[i][0],
                  place->corners[i][1]);
    each += b;
  }
  const double pitch = std::hypot(e.corners[1].x - e.corners[0].x,
                                  e.corners[1].y - e.corners[0].y) / 6;
  std::printf("  findChart: found, corners from the hand ones mean %.1f px, max %.1f px "
              "(patch pitch %.0f px; corners 0 5 23 18: %s)\n", mean, worst, pitch, each.c_str());
}

}  // namespace

int main(int argc, char** argv) {
  try {
    const std::string dir = argc > 1 ? argv[1] : SURROGATE_COLOUR_REAL_DIR;
    // The photographs are public third-party files kept out of the repository (SOURCE.md);
    // the corners measured on them are ours and are.
    const std::string corners = std::ifstream(dir + "/corners.txt") ? dir + "/corners.txt"
                                                                   : std::string(SURROGATE_COLOUR_REAL_DIR) + "/corners.txt";
    const std::vector<Entry> entries = readCorners(corners);
    std::printf("CIEDE2000 mean/max(patch of the max) over the 24 patches; white point fixed by "
                "patches 19..22\n");
    std::printf("%-25s %-9s %-30s %-15s | %-15s %-15s | %-15s %-15s\n", "image", "edition",
                "reference", "uncorrected", "matrix fit", "matrix loo", "rootp fit", "rootp loo");
    for (const Entry& e : entries) {
      if (!std::ifstream(dir + "/" + e.file)) {
        std::printf("%-25s not in %s (tests/data/colour-real/SOURCE.md says where it comes from)\n",
                    e.file.c_str(), dir.c_str());
        continue;
      }
      const Image im = image::decodeImage(dir + "/" + e.file, image::RawDecodeSettings{});
      const Measured m = measure(im, e.corners);
      for (const std::string& id : chartReferenceIds()) {
        const ChartReference& ref = chartReference(id);
        const std::array<Rgb, kChartPatches> target = referenceLinearSrgb(ref);
        const std::vector<Rgb> reference(target.begin(), target.end());
        double measuredY = 0, referenceY = 0;
        for (int k : kNeutrals) measuredY += luminance(m.rgb[k]), referenceY += luminance(target[k]);
        std::vector<Rgb> scaled = m.rgb;
        for (Rgb& c : scaled)
          for (double& v : c) v *= referenceY / measuredY;
        std::string cells[4];
        int i = 0;
        for (ColourModelKind kind : {ColourModelKind::Matrix, ColourModelKind::RootPolynomial}) {
          const ColourModel model = fitColourModel(m.rgb, reference, kind, kNeutrals);
          std::vector<Rgb> fitted;
          for (const Rgb& c : m.rgb) fitted.push_back(model.apply(c));
          cells[i++] = cell(figures(fitted, ref));
          cells[i++] = cell(figures(leaveOneOut(m.rgb, reference, kind, kNeutrals), ref));
        }
        std::printf("%-25s %-9s %-30s %-15s | %-15s %-15s | %-15s %-15s\n", e.file.c_str(),
                    e.edition.c_str(), id.c_str(), cell(figures(scaled, ref)).c_str(),
                    cells[0].c_str(), cells[1].c_str(), cells[2].c_str(), cells[3].c_str());
      }
      if (m.clipped > 0)
        std::printf("  %d patch(es) with more than 1 %% of samples at full scale\n", m.clipped);
      printFindChart(im, e);
    }
  } catch (const Error& err) {
    std::fprintf(stderr, "chart_models: %s\n", err.text().c_str());
    return 1;
  }
  return 0;
}
