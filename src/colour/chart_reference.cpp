// Reference values of the ColorChecker Classic, both editions. See chart_reference.h.
//
// Sources (CIELAB D50, 2 degree observer, as X-Rite publishes them):
//   colorchecker-classic-2014: X-Rite (2015/2016), "New color specifications for ColorChecker SG
//     and Classic Charts" (xritephoto.com support note 5884), the values for charts made after
//     November 2014 (i1Pro 2, M0), two decimals.
//   colorchecker-classic-pre-2014: X-Rite's values for charts made before November 2014, from
//     the same note; they match GretagMacbeth's 2005 reference data (BabelColor, D. Pascale,
//     "RGB coordinates of the Macbeth ColorChecker", 2006), three decimals.
// Both tables as transcribed in the colour-science dataset (colour.characterisation,
// DATA_COLORCHECKER24_{BEFORE,AFTER}_NOV2014_CIE_LAB), which cites the X-Rite note, except blue
// sky's b* before 2014: -21.925 as BabelColor gives it (colour-science has -21.905, foliage's b*
// with the sign changed); only -21.925 gives the 2005 xyY table's y = 0.3016 (tests/colour).
#include "colour/chart_reference.h"

#include "core/error.h"

namespace surrogate::colour {
namespace {

const std::array<std::string, kChartPatches> kNames = {
    "dark skin",         "light skin",        "blue sky",           "foliage",
    "blue flower",       "bluish green",      "orange",             "purplish blue",
    "moderate red",      "purple",            "yellow green",       "orange yellow",
    "blue",              "green",             "red",                "yellow",
    "magenta",           "cyan",              "white 9.5 (.05 D)",  "neutral 8 (.23 D)",
    "neutral 6.5 (.44 D)", "neutral 5 (.70 D)", "neutral 3.5 (1.05 D)", "black 2 (1.5 D)"};

const std::vector<ChartReference>& references() {
  static const std::vector<ChartReference> all = {
      {"colorchecker-classic-2014",
       "ColorChecker Classic (charts made after November 2014)",
       "X-Rite, New color specifications for ColorChecker SG and Classic Charts (2016): "
       "CIELAB D50 for charts made after November 2014",
       kNames,
       {{{37.54, 14.37, 14.92},  {64.66, 19.27, 17.50},  {49.32, -3.82, -22.54},
         {43.46, -12.74, 22.72}, {54.94, 9.61, -24.79},  {70.48, -32.26, -0.37},
         {62.73, 35.83, 56.50},  {39.43, 10.75, -45.17}, {50.57, 48.64, 16.67},
         {30.10, 22.54, -20.87}, {71.77, -24.13, 58.19}, {71.51, 18.24, 67.37},
         {28.37, 15.42, -49.80}, {54.38, -39.72, 32.27}, {42.43, 51.05, 28.62},
         {81.80, 2.67, 80.41},   {50.63, 51.28, -14.12}, {49.57, -29.71, -28.32},
         {95.19, -1.03, 2.93},   {81.29, -0.57, 0.44},   {66.89, -0.75, -0.06},
         {50.76, -0.13, 0.14},   {35.63, -0.46, -0.48},  {20.64, 0.07, -0.46}}}},
      {"colorchecker-classic-pre-2014",
       "ColorChecker Classic (charts made before November 2014)",
       "X-Rite, New color specifications for ColorChecker SG and Classic Charts (2016): "
       "CIELAB D50 for charts made before November 2014 (GretagMacbeth's 2005 values)",
       kNames,
       {{{37.986, 13.555, 14.059},  {65.711, 18.130, 17.810},   {49.927, -4.880, -21.925},
         {43.139, -13.095, 21.905}, {55.112, 8.844, -25.399},   {70.719, -33.397, -0.199},
         {62.661, 36.067, 57.096},  {40.020, 10.410, -45.964},  {51.124, 48.239, 16.248},
         {30.325, 22.976, -21.587}, {72.532, -23.709, 57.255},  {71.941, 19.363, 67.857},
         {28.778, 14.179, -50.297}, {55.261, -38.342, 31.370},  {42.101, 53.378, 28.190},
         {81.733, 4.039, 79.819},   {51.935, 49.986, -14.574},  {51.038, -28.631, -28.638},
         {96.539, -0.425, 1.186},   {81.257, -0.638, -0.335},   {66.766, -0.734, -0.504},
         {50.867, -0.153, -0.270},  {35.656, -0.421, -1.231},   {20.461, -0.079, -0.973}}}},
  };
  return all;
}

}  // namespace

const ChartReference& chartReference(const std::string& id) {
  for (const ChartReference& r : references())
    if (r.id == id) return r;
  std::string known;
  for (const ChartReference& r : references()) known += (known.empty() ? "" : ", ") + r.id;
  throw Error(ErrorKind::Usage, id, "chart reference",
              "no chart reference of that name; the known ones are " + known);
}

std::vector<std::string> chartReferenceIds() {
  std::vector<std::string> ids;
  for (const ChartReference& r : references()) ids.push_back(r.id);
  return ids;
}

std::array<Rgb, kChartPatches> referenceLinearSrgb(const ChartReference& reference) {
  // Lab D50 -> XYZ D50 -> Bradford -> XYZ D65 -> linear sRGB. Out-of-gamut values (cyan's red
  // goes a little below 0) are kept: clipping them would move the target of the fit.
  std::array<Rgb, kChartPatches> rgb{};
  for (int k = 0; k < kChartPatches; ++k) rgb[k] = linearSrgbFromLabD50(reference.lab[k]);
  return rgb;
}

}  // namespace surrogate::colour
