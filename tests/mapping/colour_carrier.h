// The sample capture (tests/archive/sample_capture.h) with a ColourCorrection step patched into
// its carrier, as the stage records it (docs/carrier.md, "ColourCorrection"): for the mapping
// tests of colour from a chart. Example:
//   const colourcarrier::Sample s = colourcarrier::sample("colour", colourcarrier::Outcome::Corrected);
//   mapping::deriveMets(s.carrierXml, s.facts);   // event-s9 is the colour correction
#pragma once

#include <filesystem>
#include <string>

#include "mapping/mapping.h"

namespace colourcarrier {

enum class Outcome { Corrected, NoChart };

struct Sample {
  std::filesystem::path capture;
  std::string carrierXml;
  surrogate::mapping::PackageFacts facts;
  std::string chartFileId;  // the file the chart was found (or searched for) in
  std::string firstSha256;  // of the carrier's first file: the capture identifier's
};

// Step s9 (ColourCorrection 1) between ingest and the fit, with its result. Corrected: the
// chart found in jpeg-exports/IMG_0001.jpg, two patches (one measured), the figures
// 6.3/10.1 before, 1.2/3.1 after, 1.4/3.5 held out, and two quality levels. NoChart: the search
// of that image found none.
Sample sample(const std::string& name, Outcome outcome);

}  // namespace colourcarrier
