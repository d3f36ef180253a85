// The report's table of the learned fits (LearnedFit steps, stages/learned_fit_stage.h): their
// folder, PSNR at the captured lights and leaving each photograph out, and, when the step was
// asked to (holdout), PSNR and SSIM at photographs left out of a second fit beside the blend of
// the three nearest photographs, the figure any model should beat (docs/hrti-math.md, "Quality
// at unseen lights").
#include <map>
#include <sstream>

#include "core/error.h"
#include "report/explain.h"
#include "report/html.h"
#include "report/sections.h"

namespace surrogate::report {

std::map<std::string, double> numericValues(const carrier::Result& result) {
  std::map<std::string, double> v;
  for (const carrier::DataItem* item : result.itemsOf("value")) {
    try {
      v[item->get("name").value_or("")] = item->number("value");
    } catch (const Error&) {
      // a figure that is not a number is shown as "-"
    }
  }
  return v;
}

std::string learnedFitsTable(const carrier::Carrier& c) {
  std::ostringstream rows;
  bool heldOut = false;
  for (const carrier::Step& step : c.process) {
    if (step.component != "LearnedFit") continue;
    const carrier::Result* r = c.findResult(step.id);
    if (!r) continue;
    std::map<std::string, double> v = numericValues(*r);
    const auto shown = [&](const char* name, int digits) {
      const auto it = v.find(name);
      return it == v.end() ? std::string("-") : displayNumber(it->second, digits);
    };
    const std::string folder = "finished-files/" + step.param("basis", "?") + "/";
    rows << "<tr><td>" << escapeHtml(stepTitle(step)) << "</td><td><code>" << escapeHtml(folder) << "</code></td><td class=\"num\">"
         << shown("psnr", 2) << "</td><td class=\"num\">" << shown("leaveOneOutPsnr", 2) << "</td>";
    if (v.count("heldOutPsnr")) {
      heldOut = true;
      rows << "<td class=\"num\">" << shown("heldOutImages", 0) << "</td><td class=\"num\">" << shown("heldOutPsnr", 2)
           << " / " << shown("heldOutSsim", 3) << "</td><td class=\"num\">" << shown("nearestBlendPsnr", 2) << " / "
           << shown("nearestBlendSsim", 3) << "</td><td>" << explainPsnr(v["heldOutPsnr"]) << "</td></tr>";
    } else {
      rows << "<td class=\"num\">-</td><td class=\"num\">-</td><td class=\"num\">-</td><td>not measured (run with "
              "--holdout K to leave K photographs out and relight their lights)</td></tr>";
    }
  }
  if (rows.str().empty()) return "";
  return std::string("<table class=\"learned-fits\"><tr><th>learned fit</th><th>web layout</th>"
                     "<th>PSNR at the captured lights (dB)</th><th>PSNR leaving each photograph out (dB)</th>"
                     "<th>photographs left out</th><th>PSNR (dB) / SSIM at their lights</th>"
                     "<th>3 nearest photographs blended</th><th>what it means</th></tr>") +
         rows.str() + "</table>" +
         (heldOut ? "<p class=\"note\">Left out: photographs spread over the light directions, not seen by a "
                    "second fit; the model relit at their lights as a viewer shows it (its JPEG planes), "
                    "compared with them.</p>"
                  : "");
}

}  // namespace surrogate::report
