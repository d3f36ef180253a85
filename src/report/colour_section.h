// Private to src/report: the "Colour" section, from what the colour step (ColourCorrection)
// records (carrier/colour_summary.h): the chart's edition, where it was found or given, the
// model, CIEDE2000 before and after and held out, the guidelines' levels, and the chart itself
// patch by patch as HTML swatches (reference, corrected, as photographed) with each patch's
// CIEDE2000 under it; one sentence when the colours were kept.
//
//   page << colourSection(carrier);   // "" for a carrier without a colour step
#pragma once

#include <string>

#include "carrier/carrier.h"
#include "carrier/colour_summary.h"

namespace surrogate::report {

// The section, or "" when the carrier has no colour step (carriers before it existed).
std::string colourSection(const carrier::Carrier& c);

// A recorded L*a*b* (D50) as the 8-bit sRGB a screen shows it, "#rrggbb": Bradford-adapted to
// D65 (colour::linearSrgbFromLabD50), encoded and rounded, each channel clipped to 0..255.
// `clipped` (when given) says whether a channel was outside sRGB before clipping.
std::string srgbHex(const carrier::LabValues& lab, bool* clipped = nullptr);

}  // namespace surrogate::report
