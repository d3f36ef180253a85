#include "report/relight_section.h"

#include <algorithm>
#include <cmath>
#include <optional>
#include <sstream>

#include "core/error.h"
#include "core/parallel.h"
#include "report/embed.h"
#include "report/html.h"
#include "report/learned_relight.h"
#include "report/outputs.h"
#include "report/sections.h"

namespace surrogate::report {

namespace {

// A learned model's info.json (LearnedFit: finished-files/<basis>/info.json).
bool isLearnedInfo(const std::string& kind) { return kind == "learned-model"; }

// The fitted models (.ptm, .rti HSH and the learned layouts' info.json) the carrier lists as
// outputs, in carrier order.
std::vector<const carrier::FileRecord*> fittedModels(const carrier::Carrier& c) {
  std::vector<const carrier::FileRecord*> out;
  for (const auto& [kind, file] : outputsByKind(c))
    if (file->format.rfind("PTM_FORMAT", 0) == 0 || file->format == "RTI_HSH" || isLearnedInfo(kind))
      if (std::find(out.begin(), out.end(), file) == out.end()) out.push_back(file);
  return out;
}

}  // namespace

std::size_t relightModelCount(const carrier::Carrier& c) { return fittedModels(c).size(); }

std::vector<RelightModel> relightModels(const carrier::Carrier& c, const ReportSource& source,
                                        const ReportOptions& options) {
  const std::vector<const carrier::FileRecord*> files = fittedModels(c);
  const std::size_t share = relightShare(options.relightModelsBytes, files.size());
  std::vector<RelightModel> out(files.size());
  parallelFor(files.size(), 1, effectiveThreads(options.threads), [&](std::size_t begin, std::size_t end) {
    for (std::size_t k = begin; k < end; ++k) {
      RelightModel& m = out[k];
      m.file = files[k];
      if (options.relightCopies) {
        const auto copy = options.relightCopies->find(m.file->path);
        if (copy != options.relightCopies->end() && copy->second.maxSide == options.relightMaxSide &&
            copy->second.maxBytes == share) {
          m.found = true;
          m.copied = &copy->second.json;
          continue;
        }
      }
      try {
        if (m.file->format == "JSON") {  // a learned layout: its info.json and planes
          const std::optional<std::string> json =
              learnedRelightJson(c, source, *m.file, options.relightMaxSide, share);
          m.found = json.has_value();
          if (json) m.made = *json;
          continue;
        }
        const std::optional<std::string> bytes = source.read(m.file->path);
        m.found = bytes.has_value();
        if (!bytes) continue;
        m.made = relightJson(*bytes, options.relightMaxSide, m.file->path, share);
      } catch (const Error& e) {
        m.found = true;
        m.problem = e.text();
      }
    }
  });
  return out;
}


std::optional<std::array<double, 3>> meanLightDirection(const std::vector<LightPoint>& lights) {
  constexpr double kDegree = 3.14159265358979323846 / 180;
  double x = 0, y = 0, z = 0;
  for (const LightPoint& l : lights) {
    const double e = l.elevationDeg * kDegree, a = l.azimuthDeg * kDegree;
    x += std::cos(e) * std::cos(a);
    y += std::cos(e) * std::sin(a);
    z += std::sin(e);
  }
  const double n = std::sqrt(x * x + y * y + z * z);
  // Below this length the directions cancel out (opposite lights): no direction to start at.
  constexpr double kCancelled = 1e-9;
  if (lights.empty() || !(n > kCancelled * static_cast<double>(lights.size()))) return std::nullopt;
  return std::array<double, 3>{x / n, y / n, z / n};
}

RelightSection relightSection(const carrier::Carrier& c, const std::vector<RelightModel>& models,
                              const std::vector<LightPoint>& lights, Report& report) {
  std::ostringstream s, notes, buttons;
  RelightSection section;
  s << "<section id=\"relight\"><h2>Relight it yourself</h2>";
  for (const RelightModel& model : models) {
    if (!model.found) {
      notes << "<p class=\"note\">The model " << escapeHtml(model.file->path) << " is not in this package or capture.</p>";
      continue;
    }
    if (model.json().empty()) {
      notes << "<p class=\"bad\">The model cannot be shown: " << escapeHtml(model.problem) << "</p>";
      continue;
    }
    section.models.push_back(&model.json());
    const carrier::Step* fit = c.findStep(model.file->createdBy);
    buttons << "<button type=\"button\" data-model=\"" << section.models.size() - 1 << "\" title=\""
            << escapeHtml(model.file->path) << "\">"
            << escapeHtml(fit ? modelTitle(fit->param("basis", "")) : model.file->path) << "</button>";
  }
  const std::size_t shown = section.models.size();
  if (shown == 0) {
    const std::string none = notes.str().empty()
                                 ? std::string("<p class=\"note\">No model was fitted, so there is no interactive view.</p>")
                                 : notes.str();
    s << none << "</section>";
    section.before = s.str();
    return section;
  }
  report.relightable = true;
  std::string start;
  if (const auto mean = meanLightDirection(lights)) {
    std::ostringstream v;
    v.precision(6);
    v << " data-start-light=\"" << (*mean)[0] << "," << (*mean)[1] << "," << (*mean)[2] << "\"";
    start = v.str();
  }
  s << "<div class=\"relight\"><div class=\"relight-view\"><canvas id=\"relight-canvas\"" << start << "></canvas>"
       "<p id=\"relight-caption\" class=\"note\"></p></div><div class=\"relight-controls\">"
    << (shown > 1 ? "<div id=\"model-choice\" role=\"group\" aria-label=\"model\">" + buttons.str() + "</div>" : "")
    << "<canvas id=\"light-pad\" width=\"260\" height=\"260\" aria-label=\"light direction\"></canvas>"
       "<p id=\"light-readout\"></p><p class=\"note\">Drag on the disc or on the picture to move the "
       "light. The disc is drawn as the light directions' plot: the centre is a light on the camera's "
       "axis, the rim grazing light, rings every 30\u00b0 of elevation; azimuth 0\u00b0 to the right, 90\u00b0 at "
       "the top, \u221290\u00b0 at the bottom.</p>"
    << notes.str() << "</div></div><script type=\"application/json\" id=\"relight-data\">[";
  section.before = s.str();
  section.after = "]</script></section>";
  return section;
}

}  // namespace surrogate::report
