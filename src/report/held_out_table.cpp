// The report's comparison of the fitted bases at lights left out (`--holdout K`, recorded by
// RtiFit and LearnedFit: stages/held_out_record.h), so that a conservator can choose a basis on
// evidence: per fit, PSNR and SSIM at the photographs a second fit did not see, beside the blend
// of the three nearest photographs (docs/hrti-math.md, "Quality at unseen lights"). Shown when a
// PTM or HSH fit was measured; the learned fits' own table (learned_fits.cpp) carries theirs.
#include <map>
#include <sstream>

#include "core/error.h"
#include "report/explain.h"
#include "report/html.h"
#include "report/sections.h"

namespace surrogate::report {

std::string heldOutTable(const carrier::Carrier& c) {
  std::ostringstream rows;
  bool classic = false;
  for (const carrier::Step& step : c.process) {
    if (step.component != "RtiFit" && step.component != "LearnedFit") continue;
    const carrier::Result* r = c.findResult(step.id);
    if (!r) continue;
    const std::map<std::string, double> v = numericValues(*r);
    if (!v.count("heldOutPsnr")) continue;
    classic = classic || step.component == "RtiFit";
    const auto shown = [&](const char* name, int digits) {
      const auto it = v.find(name);
      return it == v.end() ? std::string("-") : displayNumber(it->second, digits);
    };
    rows << "<tr><td>" << escapeHtml(stepTitle(step)) << "</td><td class=\"num\">" << shown("heldOutImages", 0)
         << "</td><td class=\"num\">" << shown("heldOutPsnr", 2) << " / " << shown("heldOutSsim", 3)
         << "</td><td class=\"num\">" << shown("nearestBlendPsnr", 2) << " / " << shown("nearestBlendSsim", 3)
         << "</td></tr>";
  }
  if (!classic) return "";
  return "<h3>At lights left out of the fit</h3><table class=\"held-out\"><tr><th>fit</th><th>photographs left "
         "out</th><th>PSNR (dB) / SSIM at their lights</th><th>3 nearest photographs blended</th></tr>" +
         rows.str() +
         "</table><p class=\"note\">Each fit was made again without these photographs (spread over the light "
         "directions, the lowest first) and relit at their lights, as a viewer shows it; higher is closer. The "
         "same photographs are left out for every fit, so the rows compare the bases on this capture. A basis "
         "below the blend of the nearest photographs adds nothing between the lights but compactness.</p>";
}

}  // namespace surrogate::report
