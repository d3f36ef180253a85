// ColourSummary: what a carrier's colour step (ColourCorrection, stages/colour_chart_stage.h)
// records, as plain data, for `surrogate info` and the report's colour section; both show the
// same figures, so they read them once, here.
//
//   if (const auto colour = carrier::describeColour(c))
//     if (colour->corrected) std::cout << colour->referenceTitle << ": " << *colour->meanAfter << "\n";
//
// Only what the carrier says: the carrier library knows no colour science, so Lab values stay
// the recorded numbers (L*, a*, b* under D50) and nothing is recomputed.
#pragma once

#include <array>
#include <optional>
#include <string>
#include <vector>

#include "carrier/carrier.h"

namespace surrogate::carrier {

using LabValues = std::array<double, 3>;  // L*, a*, b* (D50), as recorded

// One of the chart's patches (chartPatch), by its index on the chart (0 dark skin .. 23 black).
// A patch that could not be measured has only its index, name and reference (frames 0).
struct ColourPatch {
  int index = 0;
  std::string name;
  std::optional<LabValues> reference, before, corrected;
  std::optional<double> deltaE2000Before, deltaE2000, deltaE2000HeldOut;
  int frames = 0;
};

struct ColourSummary {
  std::string step;     // the step's id
  std::string chart;    // "auto", "none" or the image named (the step's value "chart")
  // The recorded outcome: "corrected", or the sentence saying why the colours were kept; for
  // chart=none (which records none) a sentence saying so.
  std::string outcome;
  bool corrected = false;
  std::string image;    // the path of the image the chart was found, given or searched in; "" when none
  std::string method;   // "found" or "given" (corrected only)
  std::optional<int> framesMeasured;
  std::string reference, referenceTitle, referenceSource, model;
  std::optional<double> meanBefore, maxBefore, meanAfter, maxAfter, meanHeldOut, maxHeldOut;
  std::vector<std::string> qualityLevels;  // "FADGI 2023: 4 star", one per guideline
  std::vector<ColourPatch> patches;        // in chart order
};

// The last ColourCorrection step's record; nullopt when the carrier has none (carriers before
// the step existed, or a run that planned none). Text that is not a number reads as absent.
std::optional<ColourSummary> describeColour(const Carrier& c);

}  // namespace surrogate::carrier
