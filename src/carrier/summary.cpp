#include "carrier/summary.h"

#include "core/sphere_reference.h"

#include <algorithm>
#include <cmath>
#include <cstdlib>

#include "core/text.h"

namespace surrogate::carrier {

std::string shownValue(const std::string& value) {
  std::string out;
  std::size_t start = 0;
  while (start <= value.size()) {
    const std::size_t comma = std::min(value.find(',', start), value.size());
    const std::string part = value.substr(start, comma - start);
    char* end = nullptr;
    const double v = std::strtod(part.c_str(), &end);
    if (part.empty() || end != part.c_str() + part.size() || !std::isfinite(v)) return value;
    std::string t = fixedDecimals(v, 1);
    if (t.size() > 2 && t.compare(t.size() - 2, 2, ".0") == 0) t.resize(t.size() - 2);
    out += (out.empty() ? "" : ",") + t;
    start = comma + 1;
  }
  return out;
}

std::string interventionText(const Intervention& i) {
  if (i.kind == "exclude-image") return i.target + " is left out of every step";
  // Spheres counted from 1, as people count them (core/sphere_reference.h); the carrier's
  // targets count from 0.
  if (i.kind == "manual-sphere")
    return "circle of sphere " + sphereNumberText(i.target) + " given by hand (x,y,r " + shownValue(i.value) + ")";
  if (i.kind == "manual-highlight") {
    const auto colon = i.target.rfind(':');
    const std::string image = i.target.substr(0, colon), sphere = colon == std::string::npos ? "" : i.target.substr(colon + 1);
    return "highlight of " + image + (sphere.empty() ? "" : " on sphere " + sphereNumberText(sphere)) + " given by hand (x,y " +
           shownValue(i.value) + ")";
  }
  if (i.kind == "accept-changed-original") return "the changed " + i.target + " accepted as it is now";
  return i.target + (i.value.empty() ? "" : " = " + shownValue(i.value));
}

CarrierSummary describeCarrier(const Carrier& c) {
  CarrierSummary s;
  s.title = c.header.title;
  s.created = c.header.created;
  s.modified = c.header.modified;
  s.hostname = c.header.machine.hostname;
  s.rights = c.header.rights;
  s.license = c.header.license;
  s.creators = c.header.creators;
  s.metadata = c.header.meta;
  s.files = c.files.size();
  for (const FileRecord& f : c.files) s.images += f.imageSize.has_value();
  for (const Step& step : c.process) {
    const Result* r = c.findResult(step.id);
    s.steps.push_back({step.id, step.component, step.version, r ? r->status : "not run", r ? r->seconds : 0.0,
                       step.interventions.size()});
  }
  // The decisions that stand, those a failed last run was given included.
  for (const Step& step : standingProcess(c)) {
    for (const Intervention& i : step.interventions) {
      DecisionSummary d{step.id, step.component, i, interventionText(i)};
      if (i.kind == "exclude-image") s.exclusions.push_back(d);
      s.decisions.push_back(std::move(d));
    }
    if (step.component == "CaptureIngest" && step.hasParam("lp")) s.domeLights.push_back(step.param("lp"));
  }
  s.runs = c.header.runs;
  for (const LogEntry& e : c.log) {
    if (e.level != "warning") continue;
    const Step* step = c.findStep(e.step);
    s.warnings.push_back({e.step, step ? step->component : "", e.time, e.text});
  }
  return s;
}

}  // namespace surrogate::carrier
