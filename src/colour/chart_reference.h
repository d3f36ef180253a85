// Reference values of the charts Surrogate measures: the ColorChecker Classic (24 patches),
// in the two formulations X-Rite has published (the pigments changed in November 2014, and
// the values with them: a chart's edition must be recorded with every measurement).
//
// Patch order: row by row from the top-left as the chart is normally held (dark skin, light
// skin, blue sky, ... ; the bottom row white 9.5 to black 2): index 0..23, columns 0..5, rows
// 0..3. Values are CIELAB under D50, 2 degree observer, as the manufacturer publishes them.
//
//   const ChartReference& ref = chartReference("colorchecker-classic-2014");
//   Lab white = ref.lab[18];
#pragma once

#include <array>
#include <string>
#include <vector>

#include "colour/colour_space.h"

namespace surrogate::colour {

inline constexpr int kChartColumns = 6;
inline constexpr int kChartRows = 4;
inline constexpr int kChartPatches = kChartColumns * kChartRows;
// The neutral patches (bottom row): white 9.5 (18) .. black 2 (23).
inline constexpr int kFirstNeutral = 18;

struct ChartReference {
  std::string id;           // "colorchecker-classic-2014", "colorchecker-classic-pre-2014"
  std::string title;        // what a report names it by
  std::string source;       // where the values come from (publisher, document, date)
  std::array<std::string, kChartPatches> patchNames;  // "dark skin", ...
  std::array<Lab, kChartPatches> lab;                 // D50
};

// The edition a run uses unless told otherwise (charts sold since November 2014).
inline constexpr const char* kDefaultChartReference = "colorchecker-classic-2014";

// The reference with this id; Error(Usage) listing the known ids otherwise.
const ChartReference& chartReference(const std::string& id);
std::vector<std::string> chartReferenceIds();

// Linear sRGB (D65, via Bradford) of each reference patch: what a perfectly corrected image
// holds where the chart is, at the exposure that puts the chart's white at its reference Y.
std::array<Rgb, kChartPatches> referenceLinearSrgb(const ChartReference& reference);

}  // namespace surrogate::colour
