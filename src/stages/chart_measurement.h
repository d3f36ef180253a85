// A chart measured across the frames of an RTI capture: each patch's linear RGB as a light
// along the chart's normal would show it, the same quantity as the fitted model's albedo.
//
// In frame i a flat, matte patch shows v_i = A e_i + B per channel, where e_i is the light's
// irradiance factor at the patch (the cosine of its angle to the chart's normal, times its
// inverse-square fall-off for a near light; 1 for a light along the normal at the frame
// centre's distance) and B the room's light. A least-squares line through the frames' (e_i,
// v_i), refitted once without the frames whose residual exceeds 4 robust deviations (a sphere's
// shadow across the patch, a glint), gives the value at e = 1: A + B. With fewer than
// kMinFramesForLine usable frames, the median of v_i / e_i.
//
//   std::vector<FrameReading> frames = ...;                  // one per frame measured
//   ChartMeasurement m = measureAtNormalIncidence(frames);
//   colour::Rgb white = m.patches[18].value;
#pragma once

#include <array>
#include <string>
#include <vector>

#include "colour/chart_detection.h"

namespace surrogate::stages {

inline constexpr int kMinFramesForLine = 4;
// Frames lit more obliquely than this at a patch are left out (a grazing light shows the
// chart's texture and the room more than its colour).
inline constexpr double kMinIrradianceFactor = 0.2;

struct FrameReading {
  int image = 0;                      // index in the capture's input images
  colour::ChartReading reading;
  std::array<double, colour::kChartPatches> irradiance{};  // e of each patch
  bool usable = true;                 // false: the frame's chart is unevenly lit (all patches out)
};

struct PatchMeasurement {
  colour::Rgb value{0, 0, 0};  // linear, at e = 1
  int frames = 0;              // frames that measured it (after the outliers left out)
  bool measured = false;       // false: no usable frame (clipped everywhere, or never lit)
};

struct ChartMeasurement {
  std::array<PatchMeasurement, colour::kChartPatches> patches;
  int framesUsable = 0;
};

ChartMeasurement measureAtNormalIncidence(const std::vector<FrameReading>& frames);

}  // namespace surrogate::stages
