#include "generator/chart.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <sstream>

#include "colour/chart_reference.h"
#include "core/error.h"

namespace surrogate::generator {

namespace {

// The chart's own coordinates: u along its rows (patch 0 towards patch 5), v down its columns
// (patch 0 towards patch 18), origin at patch 0's outer corner, pixels.
struct Frame {
  double cx, cy, cosA, sinA, gridW, gridH;
};

Frame frameOf(const ChartTruth& c) {
  const double a = c.angleDeg * M_PI / 180;
  const double gw = 6 * c.patchSide + 5 * c.gap, gh = 4 * c.patchSide + 3 * c.gap;
  const double cx = (c.corners[0][0] + c.corners[2][0]) / 2, cy = (c.corners[0][1] + c.corners[2][1]) / 2;
  return {cx, cy, std::cos(a), std::sin(a), gw, gh};
}

std::array<double, 2> toImage(const Frame& f, double u, double v) {
  const double du = u - f.gridW / 2, dv = v - f.gridH / 2;
  return {f.cx + f.cosA * du - f.sinA * dv, f.cy + f.sinA * du + f.cosA * dv};
}

std::array<double, 2> toChart(const Frame& f, double x, double y) {
  const double dx = x - f.cx, dy = y - f.cy;
  return {f.cosA * dx + f.sinA * dy + f.gridW / 2, -f.sinA * dx + f.cosA * dy + f.gridH / 2};
}

// -2 outside the chart, -1 on its black (gaps, frame), else the patch's index.
int classify(const ChartTruth& c, const Frame& f, double u, double v) {
  if (u < -c.border || v < -c.border || u > f.gridW + c.border || v > f.gridH + c.border) return -2;
  const double pitch = c.patchSide + c.gap;
  const int col = static_cast<int>(std::floor(u / pitch)), row = static_cast<int>(std::floor(v / pitch));
  if (col < 0 || row < 0 || col >= colour::kChartColumns || row >= colour::kChartRows) return -1;
  if (u - col * pitch >= c.patchSide || v - row * pitch >= c.patchSide) return -1;
  return row * colour::kChartColumns + col;
}

}  // namespace

std::array<double, 9> parseColourCast(const std::string& text) {
  // warm: a tungsten-like cast, red up and blue well down, each channel picking up some of its
  // neighbours' light (a camera's cross-talk), so that no white balance alone undoes it. Left
  // uncorrected, the albedo `surrogate run` makes of a 24-shot capture has the chart about 6.3
  // dE2000 off on average, 10 at most (exposure-normalised; bench/chart_error, issue 54).
  if (text == "none") return kNoColourCast;
  if (text == "warm") return {1.10, 0.14, 0.04, 0.10, 0.88, 0.08, 0.03, 0.16, 0.72};
  if (text == "cool") return {0.80, 0.06, 0.00, 0.04, 0.94, 0.06, 0.02, 0.08, 1.14};
  std::array<double, 9> m{};
  const char* p = text.c_str();
  for (int k = 0; k < 9; ++k) {
    char* end = nullptr;
    m[k] = std::strtod(p, &end);
    const bool last = k == 8;
    if (end == p || !std::isfinite(m[k]) || std::abs(m[k]) > 10 || (last ? *end != '\0' : *end != ','))
      throw Error(ErrorKind::Usage, "--colour-cast", "command line",
                  "is none, warm, cool or nine numbers m00,m01,...,m22 (row-major, each within -10..10), not " + text);
    p = end + 1;
  }
  return m;
}

ChartTruth planChart(const GeneratorOptions& o, const std::vector<SphereTruth>& spheres) {
  ChartTruth c;
  c.reference = colour::chartReference(o.chartReference).id;  // Error(Usage) naming the known ones
  c.angleDeg = kChartAngleDeg;
  c.patchSide = kChartPatchFraction * std::min<double>(o.width, 1.5 * o.height);
  c.gap = kChartGapFraction * c.patchSide;
  c.border = kChartBorderFraction * c.patchSide;
  const double gw = 6 * c.patchSide + 5 * c.gap, gh = 4 * c.patchSide + 3 * c.gap;
  const double ow = gw + 2 * c.border, oh = gh + 2 * c.border;
  const double a = c.angleDeg * M_PI / 180, margin = std::max(12.0, c.border);
  const double halfX = (ow * std::cos(a) + oh * std::sin(a)) / 2, halfY = (ow * std::sin(a) + oh * std::cos(a)) / 2;
  const auto refuse = [&](const std::string& why) {
    throw Error(ErrorKind::Usage, "--colour-chart", "generator",
                "does not fit: " + why + "; give a larger frame (at least about 600 x 400) or smaller spheres");
  };
  if (c.patchSide < 8) refuse("its patches would be under 8 pixels");
  if (2 * halfX + 2 * margin > o.width || 2 * halfY + 2 * margin > o.height)
    refuse("the chart needs " + std::to_string(static_cast<int>(std::ceil(2 * halfX + 2 * margin))) + " x " +
           std::to_string(static_cast<int>(std::ceil(2 * halfY + 2 * margin))) + " pixels");
  const double cx = margin + halfX, cy = o.height - margin - halfY;
  const Frame f{cx, cy, std::cos(a), std::sin(a), gw, gh};
  c.corners = {toImage(f, 0, 0), toImage(f, gw, 0), toImage(f, gw, gh), toImage(f, 0, gh)};
  const double pitch = c.patchSide + c.gap;
  for (int k = 0; k < colour::kChartPatches; ++k)
    c.centres[k] = toImage(f, (k % 6) * pitch + c.patchSide / 2, (k / 6) * pitch + c.patchSide / 2);
  for (const SphereTruth& s : spheres) {
    // The sphere's disc against the chart's rectangle (frame included), in the chart's frame.
    const auto uv = toChart(f, s.cx, s.cy);
    const double du = std::max({-c.border - uv[0], 0.0, uv[0] - gw - c.border});
    const double dv = std::max({-c.border - uv[1], 0.0, uv[1] - gh - c.border});
    if (std::hypot(du, dv) < s.r + margin) refuse("a sphere stands where the chart lies (bottom-left)");
  }
  return c;
}

std::vector<std::uint8_t> paintChart(const ChartTruth& c, int w, int h, std::vector<float>* height,
                                     std::vector<std::array<float, 3>>* albedo) {
  const Frame f = frameOf(c);
  std::array<colour::Rgb, colour::kChartPatches> rgb = colour::referenceLinearSrgb(colour::chartReference(c.reference));
  for (auto& p : rgb)
    for (double& v : p) v = std::max(0.0, v);
  std::vector<std::uint8_t> flat(std::size_t(w) * h, 0);
  float top = -1e30f;
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) {
      const auto uv = toChart(f, x, y);
      if (classify(c, f, uv[0], uv[1]) == -2) continue;
      flat[std::size_t(y) * w + x] = 1;
      top = std::max(top, (*height)[std::size_t(y) * w + x]);
    }
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) {
      const std::size_t i = std::size_t(y) * w + x;
      if (!flat[i]) continue;
      (*height)[i] = top;
      // 4 x 4 samples: the patches' edges anti-aliased, as a lens would show them.
      std::array<double, 3> sum{0, 0, 0};
      for (int sy = 0; sy < 4; ++sy)
        for (int sx = 0; sx < 4; ++sx) {
          const auto uv = toChart(f, x + (sx + 0.5) / 4 - 0.5, y + (sy + 0.5) / 4 - 0.5);
          const int k = classify(c, f, uv[0], uv[1]);
          for (int ch = 0; ch < 3; ++ch)
            sum[ch] += k >= 0 ? rgb[k][ch] : k == -1 ? kChartBlack : (*albedo)[i][ch];
        }
      for (int ch = 0; ch < 3; ++ch) (*albedo)[i][ch] = static_cast<float>(sum[ch] / 16);
    }
  return flat;
}

std::string chartTruthText(const ChartTruth& c, int width, int height) {
  const colour::ChartReference& ref = colour::chartReference(c.reference);
  const auto rgb = colour::referenceLinearSrgb(ref);
  std::ostringstream s;
  char line[320];
  s << "# The ColorChecker Classic lying flat in this capture (surrogate-generate --colour-chart).\n"
       "# Pixels: x right, y down, pixel centres at integer coordinates.\n"
    << "reference " << c.reference << "\n";
  std::snprintf(line, sizeof line, "frame %d %d\nangle %.6f\npatch-side %.6f\ngap %.6f\nborder %.6f\n", width, height,
                c.angleDeg, c.patchSide, c.gap, c.border);
  s << line << "# the grid's corners: the outer corners of patches 0, 5, 23, 18 (x y each)\ncorners";
  for (const auto& p : c.corners) {
    std::snprintf(line, sizeof line, " %.6f %.6f", p[0], p[1]);
    s << line;
  }
  s << "\n# patch index centre-x centre-y side reference-L a b (D50) reference-linear-sRGB r g b (the albedo,\n"
       "# negatives painted as 0)\n";
  for (int k = 0; k < colour::kChartPatches; ++k) {
    std::snprintf(line, sizeof line, "patch %d %.6f %.6f %.6f %.4f %.4f %.4f %.6f %.6f %.6f\n", k, c.centres[k][0],
                  c.centres[k][1], c.patchSide, ref.lab[k].L, ref.lab[k].a, ref.lab[k].b, rgb[k][0], rgb[k][1], rgb[k][2]);
    s << line;
  }
  return s.str();
}

}  // namespace surrogate::generator
