// Carriers made by hand with a colour step (ColourCorrection) recorded as the step records it
// (stages/colour_chart_stage.cpp), for the report's colour section (tests/report) and `info`'s
// colour object (tests/cli).
//
//   carrier::Carrier c = colour_test::correctedCarrier();   // 24 patches, the 11th not measured
#pragma once

#include <string>

#include "carrier/carrier.h"
#include "colour/chart_reference.h"
#include "core/text.h"

namespace colour_test {

using namespace surrogate;

// The patch recorded as not measured (clipped in every frame): only index, name, reference.
inline constexpr int kUnmeasured = 10;  // yellow green
// The patch whose corrected colour is L* 50, a* 0, b* 0: sRGB 119,119,119 (#777777) in closed form.
inline constexpr int kMidGrey = 21;

inline std::string lab(const colour::Lab& l) {
  return fixedDecimals(l.L, 2) + " " + fixedDecimals(l.a, 2) + " " + fixedDecimals(l.b, 2);
}

inline void value(carrier::Result& r, const std::string& name, const std::string& v) {
  r.add("value").set("name", name).set("value", v);
}

// A carrier with a capture step and a ColourCorrection step (s2) whose result `fill` writes.
template <typename Fill>
carrier::Carrier carrierWithColourStep(const std::string& chart, Fill fill) {
  carrier::Carrier c = carrier::newCarrier("Chart capture", {});
  c.addStep("CaptureIngest", "1");
  carrier::Step& step = c.addStep("ColourCorrection", "1");
  step.setParam("chart", chart);
  carrier::FileRecord f;
  f.path = "jpeg-exports/IMG_0003.jpg";
  f.role = "export";
  f.size = 1;
  f.format = "JPEG";
  f.sha256 = std::string(64, '0');
  const std::string id = c.putFile(f);
  carrier::Result r;
  r.step = step.id;
  r.started = r.ended = "2026-01-01T12:00:00Z";
  value(r, "chart", chart);
  fill(r, id);
  c.data.push_back(r);
  return c;
}

// Corrected from the 2014 chart found in IMG_0003: patch k has dE2000 0.5 + 0.1 k after and
// 3 + 0.5 k before, its corrected colour the reference 0.5 lighter (neutral 5's L* 50, a* 0, b* 0),
// its colour as photographed the reference with a* + 3. The summary figures are set apart
// (mean 6.1 -> 1.65, max 14.6 -> 2.8, held out 2.1 and 4.3) so that none is taken for another.
inline carrier::Carrier correctedCarrier(const std::string& referenceTitle = "") {
  return carrierWithColourStep("auto", [&](carrier::Result& r, const std::string& file) {
    const colour::ChartReference& ref = colour::chartReference("colorchecker-classic-2014");
    r.add("input").set("file", file).set("kind", "chart");
    value(r, "method", "found");
    r.add("value").set("name", "corners").set("value", "100,100,400,100,400,300,100,300")
        .set("unit", "pixels x,y: dark skin, bluish green, black, white");
    value(r, "patchSide", "47.9");
    value(r, "framesMeasured", "24");
    for (int k = 0; k < colour::kChartPatches; ++k) {
      if (k == kUnmeasured) continue;
      colour::Lab corrected = ref.lab[k], before = ref.lab[k];
      corrected.L += 0.5;
      before.a += 3;
      if (k == kMidGrey) corrected = {50, 0, 0};
      r.add("chartPatch").set("index", std::to_string(k)).set("name", ref.patchNames[k])
          .set("reference", lab(ref.lab[k])).set("measured", "0.1 0.08 0.06").set("frames", "24")
          .set("before", lab(before)).set("corrected", lab(corrected))
          .set("deltaE2000Before", fixedDecimals(3 + 0.5 * k, 3)).set("deltaE2000", fixedDecimals(0.5 + 0.1 * k, 3))
          .set("deltaE2000HeldOut", fixedDecimals(0.7 + 0.1 * k, 3));
    }
    r.add("chartPatch").set("index", std::to_string(kUnmeasured)).set("name", ref.patchNames[kUnmeasured])
        .set("reference", lab(ref.lab[kUnmeasured])).set("frames", "0");
    value(r, "reference", ref.id);
    value(r, "referenceTitle", referenceTitle.empty() ? ref.title : referenceTitle);
    value(r, "referenceSource", ref.source);
    value(r, "model", "matrix");
    value(r, "coefficients", "1 0 0 0 1 0 0 0 1");
    value(r, "whitePointPatches", "5");
    value(r, "deltaE2000MeanBefore", "6.100");
    value(r, "deltaE2000MaxBefore", "14.600");
    value(r, "deltaE2000Mean", "1.650");
    value(r, "deltaE2000Max", "2.800");
    value(r, "deltaE2000MeanHeldOut", "2.100");
    value(r, "deltaE2000MaxHeldOut", "4.300");
    value(r, "qualityLevel", "FADGI 2023: 3 star");
    value(r, "qualityLevel", "Metamorfoze 2019: below every level");
    value(r, "outcome", "corrected");
  });
}

// No chart found in IMG_0003: the step's sentence and the image searched.
inline carrier::Carrier notFoundCarrier() {
  return carrierWithColourStep("auto", [](carrier::Result& r, const std::string& file) {
    value(r, "outcome", "no ColorChecker found in jpeg-exports/IMG_0003.jpg: the images keep their colours");
    r.add("input").set("file", file).set("kind", "chart-search");
  });
}

// --colour-chart none: the step records the choice and nothing else.
inline carrier::Carrier noChartCarrier() {
  return carrierWithColourStep("none", [](carrier::Result&, const std::string&) {});
}

}  // namespace colour_test
