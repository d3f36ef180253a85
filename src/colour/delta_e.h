// CIEDE2000 colour difference (CIE 142-2001), as written out by Sharma, Wu and Dalal (2005),
// "The CIEDE2000 color-difference formula: implementation notes, supplementary test data, and
// mathematical observations", with kL = kC = kH = 1. tests/colour checks it against their 34
// published pairs.
//
//   double d = deltaE2000({50, 2.6772, -79.7751}, {50, 0, -82.7485});  // 2.0425
#pragma once

#include "colour/colour_space.h"

namespace surrogate::colour {

double deltaE2000(const Lab& reference, const Lab& sample);
// CIEDE2000 with the lightness weight S_L fixed at 1, the variant the Metamorfoze Preservation
// Imaging Guidelines 2.0 judge colour accuracy by ("CIE2000 SL=1"). Added for quality_levels:
// S_L >= 1 everywhere, so this is never below deltaE2000 (it counts lightness errors of light
// and dark patches more).
double deltaE2000UnitSL(const Lab& reference, const Lab& sample);
// CIE 1976 (Euclidean in L*a*b*), which some guidelines still quote.
double deltaE76(const Lab& reference, const Lab& sample);

}  // namespace surrogate::colour
