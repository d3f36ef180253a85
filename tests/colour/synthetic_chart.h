// A ColorChecker Classic drawn with OpenCV for the chart-finding tests: known patch colours,
// black gaps and border, a textured background, any size, turn and mild perspective, and the
// true corners of the patch grid to compare findChart's with.
//
//   ChartScene s;  s.angle = 90;  s.pitch = 40;
//   DrawnChart d = drawChart(s);
//   std::optional<ChartPlace> p = findChart(d.image);   // p->corners near d.corners
#pragma once

#include <array>
#include <cstdint>

#include "colour/chart_detection.h"
#include "core/image.h"

namespace surrogate::colour::test {

struct ChartScene {
  int width = 900, height = 600;
  double cx = 450, cy = 300;  // the grid's centre
  double pitch = 48;          // patch pitch, pixels
  double gapFraction = 0.2;   // black gap between patches, fraction of the pitch
  double angle = 0;           // degrees, clockwise on the screen
  double keystone = 0;        // the right side shorter by this fraction (perspective)
  bool sixteenBit = false;
  Transfer transfer = Transfer::Srgb;
  double exposure = 1;        // linear gain on the chart (clipping tests)
  double lightGradient = 0;   // linear light from left to right: 1 - g/2 .. 1 + g/2
  unsigned seed = 1;
};

struct DrawnChart {
  Image image;
  std::array<Point, 4> corners;  // true outer corners of patches 0, 5, 23, 18
};

// X-Rite's published sRGB (8-bit) values of the ColorChecker Classic patches, as tabled in
// Wikipedia's "ColorChecker" article ("manufacturer's sRGB color values").
extern const std::array<std::array<int, 3>, 24> kDrawnSrgb;

DrawnChart drawChart(const ChartScene& scene);
// A textured picture with no chart: the same background, and optionally random coloured
// rectangles (to tempt the detector).
Image drawNoChart(int width, int height, bool rectangles, unsigned seed);

}  // namespace surrogate::colour::test
