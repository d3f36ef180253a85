// Private to src/report and src/review (whose page shows the same plot): the light directions,
// from the carrier to the hemisphere plot (hemisphere.h) and its section, "Light directions".
#pragma once

#include <string>
#include <vector>

#include "carrier/carrier.h"
#include "report/hemisphere.h"

namespace surrogate::report {

// The lights of the last step that recorded any, with the residual of the first fit that
// recorded per-image residuals.
// `fitLabel`: the title of that fit's step, when there is one.
std::vector<LightPoint> collectLights(const carrier::Carrier& c, std::string* fitLabel);

// The plot with the coverage and its gaps, and a table of every light; the points coloured by
// the residual of the fit `fitLabel` names (grey when it is empty).
std::string lightsSection(const carrier::Carrier& c, const std::vector<LightPoint>& lights,
                          const Coverage& coverage, const std::string& fitLabel);

}  // namespace surrogate::report
