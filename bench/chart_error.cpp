// chart_error: the colour error of an image where a generated capture's ColorChecker lies, as
// the figures of issue 54 give it: per patch the reference Lab, the measured Lab and CIEDE2000,
// then the mean and the largest, "absolute" and "exposure-normalised".
//
//   chart_error IMAGE TRUTH_DIR [--reference ID] [--json]
//   chart_error RUN/finished-files/albedo.png CAPTURE/truth
//
// IMAGE: an 8- or 16-bit PNG or JPEG, sRGB-encoded, of the capture's frame size (a run's
// albedo.png, a shot of jpeg-exports/). TRUTH_DIR holds colour-chart.txt (surrogate-generate
// --colour-chart): each patch's centre and side. Measured: the mean in linear light of the
// pixels whose centres lie in the central 50 % square of each patch (in the chart's own
// orientation), read straight from the truth on purpose, not through src/colour's detection.
// Lab D50 through colour::labD50FromLinearSrgb. Exposure-normalised: the measured linear RGB
// scaled by the one factor that gives the neutral patches 19..22 (neutral 8 .. neutral 3.5) the
// mean Y of the reference's (white, whose exposure varies most, and black left out), so a
// brighter or darker image is judged on its colour alone. The reference: the truth's edition
// unless --reference names another.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include <opencv2/core.hpp>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>

#include "colour/chart_reference.h"
#include "colour/colour_space.h"
#include "colour/delta_e.h"
#include "core/error.h"

using namespace surrogate;
using namespace surrogate::colour;
using Point2 = std::array<double, 2>;

namespace {

constexpr int kFirstNormalising = 19, kLastNormalising = 22;  // neutral 8 .. neutral 3.5

[[noreturn]] void fail(const std::string& message) {
  std::fprintf(stderr, "chart_error: %s\n", message.c_str());
  std::exit(2);
}

struct Truth {
  std::string reference;
  int width = 0, height = 0;
  std::array<Point2, 4> corners{};
  std::array<Point2, kChartPatches> centres{};
  std::array<double, kChartPatches> sides{};
};

Truth readTruth(const std::string& dir) {
  const std::string path = dir + "/colour-chart.txt";
  std::ifstream in(path);
  if (!in) fail(path + ": cannot be read; give the truth folder of a capture made with surrogate-generate --colour-chart");
  Truth t;
  std::array<bool, kChartPatches> seen{};
  std::string line;
  bool corners = false;
  while (std::getline(in, line)) {
    std::istringstream s(line);
    std::string key;
    if (!(s >> key) || key[0] == '#') continue;
    if (key == "reference") s >> t.reference;
    else if (key == "frame") s >> t.width >> t.height;
    else if (key == "corners") {
      for (auto& p : t.corners) s >> p[0] >> p[1];
      corners = bool(s);
    } else if (key == "patch") {
      int k = -1;
      double x, y, side;
      if (!(s >> k >> x >> y >> side) || k < 0 || k >= kChartPatches) fail(path + ": a bad patch line: " + line);
      t.centres[k] = {x, y};
      t.sides[k] = side;
      seen[k] = true;
    }
  }
  if (t.reference.empty() || t.width <= 0 || !corners || std::count(seen.begin(), seen.end(), true) != kChartPatches)
    fail(path + ": lacks the reference, the frame, the corners or one of the 24 patches");
  return t;
}

// The image as linear RGB (double), sRGB decoded.
cv::Mat readLinear(const std::string& path) {
  cv::Mat m = cv::imread(path, cv::IMREAD_UNCHANGED);
  if (m.empty()) fail(path + ": cannot be read as an image; give a PNG or JPEG");
  if (m.depth() != CV_8U && m.depth() != CV_16U) fail(path + ": is neither 8- nor 16-bit");
  if (m.channels() == 4) cv::cvtColor(m, m, cv::COLOR_BGRA2BGR);
  if (m.channels() != 3) fail(path + ": is not an RGB image (the chart's colours need three channels)");
  cv::cvtColor(m, m, cv::COLOR_BGR2RGB);
  const double full = m.depth() == CV_8U ? 255.0 : 65535.0;
  // A table of the decoded values: at most 65536 entries.
  std::vector<double> table(static_cast<std::size_t>(full) + 1);
  for (std::size_t v = 0; v < table.size(); ++v) table[v] = srgbDecode(v / full);
  cv::Mat out(m.size(), CV_64FC3);
  for (int y = 0; y < m.rows; ++y)
    for (int x = 0; x < m.cols; ++x)
      for (int c = 0; c < 3; ++c)
        out.at<cv::Vec3d>(y, x)[c] = table[m.depth() == CV_8U ? m.at<cv::Vec3b>(y, x)[c] : m.at<cv::Vec3w>(y, x)[c]];
  return out;
}

}  // namespace

namespace {

// The mean linear RGB of the central 50 % square of patch k, in the chart's orientation.
Rgb patchMean(const cv::Mat& image, const Truth& t, int k) {
  const double ux = t.corners[1][0] - t.corners[0][0], uy = t.corners[1][1] - t.corners[0][1];
  const double vx = t.corners[3][0] - t.corners[0][0], vy = t.corners[3][1] - t.corners[0][1];
  const double ul = std::hypot(ux, uy), vl = std::hypot(vx, vy), half = t.sides[k] / 4;
  const double cx = t.centres[k][0], cy = t.centres[k][1], reach = half * std::sqrt(2.0) + 1;
  Rgb sum{0, 0, 0};
  int n = 0;
  for (int y = static_cast<int>(std::floor(cy - reach)); y <= static_cast<int>(std::ceil(cy + reach)); ++y)
    for (int x = static_cast<int>(std::floor(cx - reach)); x <= static_cast<int>(std::ceil(cx + reach)); ++x) {
      if (x < 0 || y < 0 || x >= image.cols || y >= image.rows) continue;
      const double u = ((x - cx) * ux + (y - cy) * uy) / ul, v = ((x - cx) * vx + (y - cy) * vy) / vl;
      if (std::abs(u) > half || std::abs(v) > half) continue;
      const cv::Vec3d p = image.at<cv::Vec3d>(y, x);
      for (int c = 0; c < 3; ++c) sum[c] += p[c];
      ++n;
    }
  if (n == 0) fail("patch " + std::to_string(k) + " has no pixel inside the image");
  for (double& s : sum) s /= n;
  return sum;
}

double luminance(const Rgb& rgb) { return xyzD65FromLinearSrgb(rgb)[1]; }

struct Summary {
  double mean = 0, max = 0;
  int maxPatch = 0;
};

Summary summarise(const std::array<double, kChartPatches>& e) {
  Summary s;
  for (int k = 0; k < kChartPatches; ++k) {
    s.mean += e[k] / kChartPatches;
    if (e[k] > s.max) s.max = e[k], s.maxPatch = k;
  }
  return s;
}

std::string jsonString(const std::string& s) {
  std::string out = "\"";
  for (char c : s) out += (c == '"' || c == '\\') ? std::string("\\") + c : std::string(1, c);
  return out + "\"";
}

}  // namespace

int main(int argc, char** argv) {
  std::vector<std::string> files;
  std::string referenceId;
  bool json = false;
  for (int i = 1; i < argc; ++i) {
    const std::string a = argv[i];
    if (a == "--help" || a == "-h") {
      std::printf("usage: chart_error IMAGE TRUTH_DIR [--reference ID] [--json]\n");
      return 0;
    }
    if (a == "--json") json = true;
    else if (a == "--reference") {
      if (i + 1 >= argc) fail("--reference needs a chart reference id");
      referenceId = argv[++i];
    } else if (!a.empty() && a[0] == '-') fail(a + " is not an option (--reference ID, --json)");
    else files.push_back(a);
  }
  if (files.size() != 2) fail("give IMAGE and TRUTH_DIR (see --help)");
  try {
    const Truth t = readTruth(files[1]);
    const ChartReference& ref = chartReference(referenceId.empty() ? t.reference : referenceId);
    const std::array<Rgb, kChartPatches> refRgb = referenceLinearSrgb(ref);
    const cv::Mat image = readLinear(files[0]);
    if (image.cols != t.width || image.rows != t.height)
      fail(files[0] + " is " + std::to_string(image.cols) + "x" + std::to_string(image.rows) + " pixels but the capture's frame is " +
           std::to_string(t.width) + "x" + std::to_string(t.height) + ": give an image of the whole frame, not resized");
    std::array<Rgb, kChartPatches> measured;
    double yRef = 0, yMeasured = 0;
    for (int k = 0; k < kChartPatches; ++k) measured[k] = patchMean(image, t, k);
    for (int k = kFirstNormalising; k <= kLastNormalising; ++k) {
      yRef += luminance(refRgb[k]);
      yMeasured += luminance(measured[k]);
    }
    if (!(yMeasured > 0)) fail("the neutral patches 19..22 are black in " + files[0] + ": nothing to normalise by");
    const double factor = yRef / yMeasured;
    std::array<Lab, kChartPatches> labAbs, labNorm;
    std::array<double, kChartPatches> eAbs, eNorm;
    for (int k = 0; k < kChartPatches; ++k) {
      labAbs[k] = labD50FromLinearSrgb(measured[k]);
      labNorm[k] = labD50FromLinearSrgb({measured[k][0] * factor, measured[k][1] * factor, measured[k][2] * factor});
      eAbs[k] = deltaE2000(ref.lab[k], labAbs[k]);
      eNorm[k] = deltaE2000(ref.lab[k], labNorm[k]);
    }
    const Summary sa = summarise(eAbs), sn = summarise(eNorm);
    if (json) {
      std::printf("{\"image\": %s, \"reference\": %s, \"normalisingFactor\": %.6f, \"patches\": [\n", jsonString(files[0]).c_str(),
                  jsonString(ref.id).c_str(), factor);
      for (int k = 0; k < kChartPatches; ++k)
        std::printf("  {\"index\": %d, \"name\": %s, \"reference\": [%.4f, %.4f, %.4f], \"measured\": [%.4f, %.4f, %.4f], "
                    "\"dE2000\": %.4f, \"normalised\": [%.4f, %.4f, %.4f], \"dE2000Normalised\": %.4f}%s\n",
                    k, jsonString(ref.patchNames[k]).c_str(), ref.lab[k].L, ref.lab[k].a, ref.lab[k].b, labAbs[k].L, labAbs[k].a,
                    labAbs[k].b, eAbs[k], labNorm[k].L, labNorm[k].a, labNorm[k].b, eNorm[k], k + 1 < kChartPatches ? "," : "");
      std::printf("], \"absolute\": {\"mean\": %.4f, \"max\": %.4f, \"maxPatch\": %d},\n"
                  "\"exposureNormalised\": {\"mean\": %.4f, \"max\": %.4f, \"maxPatch\": %d}}\n",
                  sa.mean, sa.max, sa.maxPatch, sn.mean, sn.max, sn.maxPatch);
      return 0;
    }
    std::printf("%s against %s (%s)\n", files[0].c_str(), ref.id.c_str(), ref.title.c_str());
    std::printf("%-2s %-22s %23s %23s %6s %23s %6s\n", "#", "patch", "reference L a b", "measured L a b", "dE00",
                "normalised L a b", "dE00");
    for (int k = 0; k < kChartPatches; ++k)
      std::printf("%-2d %-22s %7.2f %7.2f %7.2f %7.2f %7.2f %7.2f %6.2f %7.2f %7.2f %7.2f %6.2f\n", k, ref.patchNames[k].c_str(),
                  ref.lab[k].L, ref.lab[k].a, ref.lab[k].b, labAbs[k].L, labAbs[k].a, labAbs[k].b, eAbs[k], labNorm[k].L,
                  labNorm[k].a, labNorm[k].b, eNorm[k]);
    std::printf("absolute:            mean dE2000 %.2f  max %.2f (%s)\n", sa.mean, sa.max, ref.patchNames[sa.maxPatch].c_str());
    std::printf("exposure-normalised: mean dE2000 %.2f  max %.2f (%s)  (linear RGB x %.4f: patches 19-22 at the reference's mean Y)\n",
                sn.mean, sn.max, ref.patchNames[sn.maxPatch].c_str(), factor);
    return 0;
  } catch (const Error& e) {
    fail(e.what());
  }
}
