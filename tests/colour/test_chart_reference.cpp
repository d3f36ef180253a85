// The chart references pinned to a table outside the code: the pre-2014 CIELAB values must give
// GretagMacbeth's 2005 xyY (D50), as tabulated by BabelColor ("RGB coordinates of the Macbeth
// ColorChecker", D. Pascale 2006) and colour-science (CCS_COLORCHECKER2005), to their 4 digits.
#include <catch2/catch.hpp>

#include <cmath>

#include "colour/chart_reference.h"
#include "core/error.h"

using namespace surrogate;
using namespace surrogate::colour;

TEST_CASE("the pre 2014 values give GretagMacbeth 2005 xyY") {
  const double xyY2005[kChartPatches][3] = {
      {0.4316, 0.3777, 0.1008}, {0.4197, 0.3744, 0.3495}, {0.2760, 0.3016, 0.1836},
      {0.3703, 0.4499, 0.1325}, {0.2999, 0.2856, 0.2304}, {0.2848, 0.3911, 0.4178},
      {0.5295, 0.4055, 0.3118}, {0.2305, 0.2106, 0.1126}, {0.5012, 0.3273, 0.1938},
      {0.3319, 0.2482, 0.0637}, {0.3984, 0.5008, 0.4446}, {0.4957, 0.4427, 0.4357},
      {0.2018, 0.1692, 0.0575}, {0.3253, 0.5032, 0.2318}, {0.5686, 0.3303, 0.1257},
      {0.4697, 0.4734, 0.5981}, {0.4159, 0.2688, 0.2009}, {0.2131, 0.3023, 0.1930},
      {0.3469, 0.3608, 0.9131}, {0.3440, 0.3584, 0.5894}, {0.3432, 0.3581, 0.3632},
      {0.3446, 0.3579, 0.1915}, {0.3401, 0.3548, 0.0883}, {0.3406, 0.3537, 0.0311}};
  const ChartReference& ref = chartReference("colorchecker-classic-pre-2014");
  const Xyz iccD50{0.9642, 1.0, 0.8249};  // the white BabelColor used
  for (int k = 0; k < kChartPatches; ++k) {
    INFO(ref.patchNames[k]);
    const Xyz xyz = xyzFromLab(ref.lab[k], iccD50);
    const double sum = xyz[0] + xyz[1] + xyz[2];
    CHECK(xyz[0] / sum == Approx(xyY2005[k][0]).margin(1.5e-4));
    CHECK(xyz[1] / sum == Approx(xyY2005[k][1]).margin(1.5e-4));
    CHECK(xyz[1] == Approx(xyY2005[k][2]).margin(1e-4));
  }
}

TEST_CASE("both editions are there with their names in chart order") {
  CHECK(chartReferenceIds() ==
        std::vector<std::string>{"colorchecker-classic-2014", "colorchecker-classic-pre-2014"});
  const ChartReference& ref = chartReference(kDefaultChartReference);
  CHECK(ref.patchNames[0] == "dark skin");
  CHECK(ref.patchNames[17] == "cyan");
  CHECK(ref.patchNames[kFirstNeutral] == "white 9.5 (.05 D)");
  CHECK(ref.patchNames[23] == "black 2 (1.5 D)");
  CHECK(ref.lab[0].L == 37.54);  // X-Rite, after November 2014: dark skin 37.54 14.37 14.92
  CHECK(ref.lab[18].b == 2.93);
  CHECK_FALSE(ref.source.empty());
  CHECK_THROWS_AS(chartReference("colorchecker-sg"), Error);
}

TEST_CASE("reference linear sRGB keeps the white Y and out of gamut cyan") {
  const ChartReference& ref = chartReference(kDefaultChartReference);
  const std::array<Rgb, kChartPatches> rgb = referenceLinearSrgb(ref);
  for (int k = 0; k < kChartPatches; ++k) {
    // Y = ((L* + 16) / 116)^3 above the knee; Bradford keeps Y of a D50-white-like colour
    // only approximately, so compare with the D65 XYZ that the path itself passes through.
    const Xyz xyz = adaptD50ToD65(xyzFromLab(ref.lab[k], kWhiteD50));
    const Xyz fromRgb = xyzD65FromLinearSrgb(rgb[k]);
    for (int i = 0; i < 3; ++i) CHECK(fromRgb[i] == Approx(xyz[i]).margin(1e-12));
  }
  const double whiteY = std::pow((95.19 + 16.0) / 116.0, 3.0);
  CHECK(xyzD65FromLinearSrgb(rgb[kFirstNeutral])[1] == Approx(whiteY).margin(2e-3));
  CHECK(rgb[17][0] < 0);  // cyan lies outside sRGB: kept, not clipped
  // Neutrals stay near neutral (the 2014 white is a little yellow: b* 2.93, so B is 5 % low).
  for (int k = kFirstNeutral; k < kChartPatches; ++k)
    CHECK(std::abs(rgb[k][0] - rgb[k][2]) < 0.06 * rgb[k][1]);
}
