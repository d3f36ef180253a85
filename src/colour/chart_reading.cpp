// Reading a placed chart: each patch's linear mean, clipping and the light's evenness, and the
// sentence saying why a reading cannot be used. See chart_detection.h.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <vector>

#include "colour/chart_detection.h"
#include "colour/chart_grid.h"

namespace surrogate::colour {
namespace {

// Linear light (0..1) of every 16-bit sample.
std::vector<double> linearTable(Transfer transfer) {
  std::vector<double> t(65536);
  for (int v = 0; v < 65536; ++v)
    t[v] = transfer == Transfer::Srgb ? srgbDecode(v / 65535.0) : v / 65535.0;
  return t;
}

double median(std::vector<double> v) {
  if (v.empty()) return 0;
  std::sort(v.begin(), v.end());
  const std::size_t n = v.size();
  return n % 2 ? v[n / 2] : (v[n / 2 - 1] + v[n / 2]) / 2;
}

std::string percent(double fraction) {
  char s[32];
  std::snprintf(s, sizeof s, "%.1f %%", 100 * fraction);
  return s;
}

}  // namespace

ChartReading readChart(const Image& image, const ChartPlace& place) {
  const std::vector<double> lin = linearTable(image.transfer);
  const double gap = gapFromPatchSide(place.corners, place.patchSide);
  const Homography h = homography(place.corners);
  const Homography back = h.inverse();
  const auto regions = patchRegions(place);
  ChartReading reading;
  std::vector<double> across, down;  // each patch's relative brightness change per chart side
  for (int k = 0; k < kChartPatches; ++k) {
    const UnitRect r = centralRect(k, gap, kCentralHalf);
    const double uc = (r.u0 + r.u1) / 2, vc = (r.v0 + r.v1) / 2;
    double x0 = 1e300, y0 = 1e300, x1 = -1e300, y1 = -1e300;
    for (const Point& p : regions[k].corners)
      x0 = std::min(x0, p[0]), y0 = std::min(y0, p[1]), x1 = std::max(x1, p[0]),
      y1 = std::max(y1, p[1]);
    const int xa = std::max(0, static_cast<int>(std::floor(x0)));
    const int ya = std::max(0, static_cast<int>(std::floor(y0)));
    const int xb = std::min(image.width - 1, static_cast<int>(std::ceil(x1)));
    const int yb = std::min(image.height - 1, static_cast<int>(std::ceil(y1)));
    Rgb sum{0, 0, 0};
    double half[4] = {0, 0, 0, 0};  // luminance sums: left, right, top, bottom
    int halfCount[4] = {0, 0, 0, 0};
    int pixels = 0, clipped = 0, black = 0;
    for (int y = ya; y <= yb; ++y)
      for (int x = xa; x <= xb; ++x) {
        const Point q = back.map(x, y);
        if (q[0] < r.u0 || q[0] > r.u1 || q[1] < r.v0 || q[1] > r.v1) continue;
        Rgb v;
        bool full = false, zero = false;
        for (int c = 0; c < 3; ++c) {
          const std::uint16_t s = image.at(x, y, image.channels == 3 ? c : 0);
          full |= s == 65535;
          zero |= s == 0;
          v[c] = lin[s];
          sum[c] += v[c];
        }
        const double lum = 0.2126 * v[0] + 0.7152 * v[1] + 0.0722 * v[2];
        const int lr = q[0] < uc ? 0 : 1, tb = q[1] < vc ? 2 : 3;
        half[lr] += lum, half[tb] += lum, ++halfCount[lr], ++halfCount[tb];
        ++pixels, clipped += full, black += zero;
      }
    PatchReading& p = reading.patches[k];
    p.pixels = pixels;
    if (pixels == 0) continue;
    for (int c = 0; c < 3; ++c) p.mean[c] = sum[c] / pixels;
    p.clipped = static_cast<double>(clipped) / pixels;
    p.black = static_cast<double>(black) / pixels;
    const double lum = 0.2126 * p.mean[0] + 0.7152 * p.mean[1] + 0.0722 * p.mean[2];
    if (lum <= 0 || p.clipped > kMaxClipped || std::min({halfCount[0], halfCount[1],
                                                          halfCount[2], halfCount[3]}) == 0)
      continue;
    // The halves' centres are half the region apart; the chart is 1 across in u and v.
    across.push_back((half[1] / halfCount[1] - half[0] / halfCount[0]) / lum / ((r.u1 - r.u0) / 2));
    down.push_back((half[3] / halfCount[3] - half[2] / halfCount[2]) / lum / ((r.v1 - r.v0) / 2));
  }
  reading.lightGradient = std::max(std::abs(median(across)), std::abs(median(down)));
  return reading;
}

std::string unusableReason(const ChartPlace& place, const ChartReading& reading) {
  const auto& names = chartReference(kDefaultChartReference).patchNames;
  const std::string byHand =
      "give the chart's corners by hand with --colour-chart IMAGE:X1,Y1,X2,Y2,X3,Y3,X4,Y4 (the "
      "outer corners of dark skin, bluish green, black and white)";
  std::vector<std::string> why;
  for (int k = 0; k < kChartPatches; ++k)
    if (reading.patches[k].pixels == 0) {
      why.push_back("patch " + std::to_string(k + 1) + " (" + names[k] +
                    ") is outside the image: " + byHand);
      break;
    }
  if (place.patchSide < kMinPatchSide)
    why.push_back("the chart's patches are " + std::to_string(std::lround(place.patchSide)) +
                  " pixels wide, fewer than the " + std::to_string(std::lround(kMinPatchSide)) +
                  " needed to measure them: re-shoot with the chart larger in the frame");
  std::string clipped;
  int count = 0;
  for (int k = 0; k < kChartPatches; ++k)
    if (reading.patches[k].clipped > kMaxClipped)
      clipped += std::string(count++ ? ", " : "") + std::to_string(k + 1) + " (" + names[k] + ", " +
                 percent(reading.patches[k].clipped) + ")";
  if (count > 0)
    why.push_back(std::string(count > 1 ? "patches " : "patch ") + clipped +
                  (count > 1 ? " have" : " has") + " more than " + percent(kMaxClipped) +
                  (count > 1 ? " of their pixels" : " of its pixels") + " at full scale (clipped): re-shoot with a lower exposure, so "
                  "that the white patch stays below full scale");
  if (reading.lightGradient > kMaxLightGradient)
    why.push_back("the light over the chart changes by " + percent(reading.lightGradient) +
                  " from one side to the other (at most " + percent(kMaxLightGradient) +
                  " is usable): light the chart evenly, or place it where the light is even, "
                  "and re-shoot");
  std::string all;
  for (const std::string& s : why) all += (all.empty() ? "" : "; ") + s;
  return all;
}

}  // namespace surrogate::colour
