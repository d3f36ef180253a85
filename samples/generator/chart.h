// The ColorChecker Classic of a generated capture (GeneratorOptions::colourChart): where it lies
// and what it paints into the scene, and the named colour casts (GeneratorOptions::colourCast).
//
// The chart lies flat on the relief in the bottom-left of the frame, turned by kChartAngleDeg
// (so that finding it is not helped by square pixels): 6 x 4 patches of side
// kChartPatchFraction of the frame's width (48 px at 1200), black gaps of kChartGapFraction of
// a patch between them and a black frame of kChartBorderFraction of a patch around them (albedo
// kChartBlack, as the printed chart's). Patch k's albedo is the reference's linear sRGB
// (colour/chart_reference.h), negatives clamped to 0. Inside the chart (frame included) the
// height is constant, the highest of the relief there, and the normal (0, 0, 1).
//
//   ChartTruth c = planChart(options, truth.spheres);   // Error(Usage) if it does not fit
//   std::vector<std::uint8_t> flat = paintChart(c, w, h, &height, &albedo);
#pragma once

#include <array>
#include <cstdint>
#include <string>
#include <vector>

#include "generator/capture_generator.h"

namespace surrogate::generator {

inline constexpr double kChartPatchFraction = 0.04;   // of the frame's width (or 1.5 x its height)
inline constexpr double kChartGapFraction = 0.2;      // of a patch
inline constexpr double kChartBorderFraction = 0.5;   // of a patch
inline constexpr double kChartAngleDeg = 3;
inline constexpr double kChartBlack = 0.03;           // the gaps' and the frame's albedo

// The chart's place for these options beside these spheres; Error(Usage) when the frame is too
// small for it or a sphere stands where it would lie.
ChartTruth planChart(const GeneratorOptions& options, const std::vector<SphereTruth>& spheres);

// Paints the chart into a relief of w x h pixels (row-major): its height and albedo. Returns the
// pixels whose centre is on the chart (1), whose normal must then be (0, 0, 1).
std::vector<std::uint8_t> paintChart(const ChartTruth& chart, int w, int h, std::vector<float>* height,
                                     std::vector<std::array<float, 3>>* albedo);

// truth/colour-chart.txt of a capture.
std::string chartTruthText(const ChartTruth& chart, int width, int height);

}  // namespace surrogate::generator
