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
// CIE 1976 (Euclidean in L*a*b*), which some guidelines still quote.
double deltaE76(const Lab& reference, const Lab& sample);

}  // namespace surrogate::colour
