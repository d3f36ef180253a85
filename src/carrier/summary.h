// CarrierSummary: what a carrier records, as plain data, for `surrogate info` and any page
// that shows a carrier without rendering it itself.
//
//   const carrier::CarrierSummary s = carrier::describeCarrier(carrier::loadCarrier(path));
//   for (const carrier::DecisionSummary& d : s.decisions) std::cout << d.what << "\n";
//
// Only what the carrier itself says: the processing choices a run would repeat need the
// stages' planning and are described there.
#pragma once

#include <cstddef>
#include <string>
#include <utility>
#include <vector>

#include "carrier/carrier.h"

namespace surrogate::carrier {

// One step of the process list with the outcome its result records.
struct StepSummary {
  std::string id, component, version;
  std::string status;  // the result's status, "not run" when it has none
  double seconds = 0;  // the result's duration, 0 when it has none
  std::size_t interventions = 0;
};

// One human intervention (a standing decision), with the step that records it and what it
// does in words (interventionText).
struct DecisionSummary {
  std::string step, component;
  Intervention intervention;
  std::string what;
};

// One warning of the carrier's log (a log entry of level "warning"), with the step that logged
// it and that step's component ("" when the log names no step of the process list).
struct WarningSummary {
  std::string step, component, time, text;
};

struct CarrierSummary {
  std::string title, created, modified, hostname, rights, license;
  std::vector<Creator> creators;
  std::vector<std::pair<std::string, std::string>> metadata;  // the user's, in given order
  std::size_t files = 0;
  std::size_t images = 0;  // files with a recorded image size
  std::vector<StepSummary> steps;
  // Every standing intervention, in step order: those of the process list, or of the list a
  // failed last run planned (standingProcess), whose step ids they then carry.
  std::vector<DecisionSummary> decisions;
  std::vector<DecisionSummary> exclusions;     // those of kind exclude-image, in step order
  std::vector<std::string> domeLights;         // the .lp of each CaptureIngest step that names one
  std::vector<RunRecord> runs;                 // oldest first
  std::vector<WarningSummary> warnings;        // in the log's order
};

CarrierSummary describeCarrier(const Carrier& c);

// What an intervention does, in words: "IMG_0003 is left out of every step", "circle of
// sphere 0 given by hand (x,y,r 339,57,45)".
std::string interventionText(const Intervention& i);

// Numbers in a carrier's text values ("339,57,45", or an old carrier's
// "326.00000000000006,70") to 0.1 for display, without a trailing ".0"; other text as it is.
std::string shownValue(const std::string& value);

}  // namespace surrogate::carrier
