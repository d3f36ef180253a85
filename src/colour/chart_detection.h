// Finding a ColorChecker Classic in a photograph, and where each of its 24 patches is.
//
// A chart's place is four corners of its patch grid in image pixels (x right, y down, pixel
// centres at integer coordinates), in the chart's own order: the outer corner of patch 0 (dark
// skin), of patch 5 (bluish green), of patch 23 (black), of patch 18 (white). Whatever the
// chart's rotation in the frame, patch k is at the same place in the grid.
//
//   std::optional<ChartPlace> p = findChart(image);       // OpenCV's mcc detector, refined
//   ChartPlace q = chartFromCorners({{{100,80},{700,90},{690,500},{95,490}}});  // by hand
//   std::array<PatchRegion, 24> r = patchRegions(*p);
//   ChartReading m = readChart(image, *p);                // linear means, clipping, evenness
#pragma once

#include <array>
#include <optional>
#include <string>

#include "colour/chart_reference.h"
#include "core/image.h"

namespace surrogate::colour {

using Point = std::array<double, 2>;

struct ChartPlace {
  std::array<Point, 4> corners;  // patch 0's, patch 5's, patch 23's, patch 18's outer corner
  std::string method;            // "found" (automatic), "given" (corners from the user)
  double patchSide = 0;          // pixels: the mean side of a patch (grid pitch minus the gap)
};

// The automatic search in one image (RGB, any transfer; 8- or 16-bit samples): nullopt when no
// chart is there. Deterministic: the same pixels give the same place at any thread count.
std::optional<ChartPlace> findChart(const Image& image);

// A place from four corners given by hand, in the order above (the grid's corners: the outer
// corners of patches 0, 5, 23 and 18). Error(Usage) naming `origin` when they do not make a
// convex quadrilateral.
ChartPlace chartFromCorners(const std::array<Point, 4>& corners, const std::string& origin);

// The part of each patch that is measured: its central area, a quadrilateral away from the
// patch's edges (and the black gaps between patches) by a margin that tolerates a few pixels'
// error in the corners.
struct PatchRegion {
  std::array<Point, 4> corners;  // in the patch's own order (as the chart's)
};
std::array<PatchRegion, kChartPatches> patchRegions(const ChartPlace& place);

// What one image shows of the chart: each patch's mean in linear light (the image's samples
// decoded through its transfer, 0..1), the fraction of its samples at full scale (clipped) or
// at 0, its pixel count, and how evenly the chart is lit.
struct PatchReading {
  Rgb mean{0, 0, 0};
  double clipped = 0;  // fraction of the region's samples at full scale in any channel
  double black = 0;    // fraction at 0
  int pixels = 0;
};
struct ChartReading {
  std::array<PatchReading, kChartPatches> patches;
  // Unevenness of the light over the chart: the relative change of brightness from one side
  // of the chart to the other (left-right and top-bottom, the larger), estimated within the
  // patches themselves (each patch's halves), so the patches' own colours do not count. 0.1
  // means one side gets 10 % more light than the other.
  double lightGradient = 0;
};
ChartReading readChart(const Image& image, const ChartPlace& place);

// Why a chart's reading cannot be used (empty: it can): too small (a patch under
// kMinPatchSide pixels), clipped (a patch with more than kMaxClipped of its samples at full
// scale), unevenly lit (lightGradient above kMaxLightGradient). The sentence says what to do.
inline constexpr double kMinPatchSide = 12;
inline constexpr double kMaxClipped = 0.01;
inline constexpr double kMaxLightGradient = 0.10;
std::string unusableReason(const ChartPlace& place, const ChartReading& reading);

}  // namespace surrogate::colour
