// Private to src/report: the output files a carrier's results record, which the detection,
// results and relighting sections show.
#pragma once

#include <string>
#include <utility>
#include <vector>

#include "carrier/carrier.h"

namespace surrogate::report {

// Output files of every result, by kind, in carrier order.
std::vector<std::pair<std::string, const carrier::FileRecord*>> outputsByKind(const carrier::Carrier& c);

}  // namespace surrogate::report
