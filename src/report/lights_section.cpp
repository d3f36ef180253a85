#include "report/lights_section.h"

#include <algorithm>
#include <cmath>
#include <map>
#include <set>
#include <sstream>

#include "core/error.h"
#include "report/html.h"
#include "report/sections.h"

namespace surrogate::report {

namespace {

constexpr double kPi = 3.14159265358979323846;

// Highlights that give a light direction (hrti::isUsable; the report does not link hrti).
bool isUsedHighlight(const std::string& flag) {
  return flag == "ok" || flag == "multiple" || flag == "manual";
}

}  // namespace

std::vector<LightPoint> collectLights(const carrier::Carrier& c, std::string* fitLabel) {
  const carrier::Result* lightResult = nullptr;
  const carrier::Result* fitResult = nullptr;
  for (const carrier::Result& r : c.data) {
    if (!r.itemsOf("light").empty()) lightResult = &r;
    if (!fitResult) {
      for (const carrier::DataItem* v : r.itemsOf("imageValue"))
        if (v->get("name") == "rmse") {
          fitResult = &r;
          break;
        }
    }
  }
  std::map<std::string, double> rmse;
  if (fitResult) {
    for (const carrier::DataItem* v : fitResult->itemsOf("imageValue")) {
      if (v->get("name") != "rmse") continue;
      try {
        rmse[v->get("image").value_or("")] = v->number("value");
      } catch (const Error&) {
        // An unreadable residual is shown as "no residual" rather than failing the page.
      }
    }
    const carrier::Step* step = c.findStep(fitResult->step);
    *fitLabel = step ? stepTitle(*step) : fitResult->step;
  }
  // The lowest confidence of the usable highlights of each image (those its light came from);
  // those given by hand have none of their own.
  std::map<std::string, double> confidence;
  std::set<std::string> byHand;
  for (const carrier::Result& r : c.data)
    for (const carrier::DataItem* h : r.itemsOf("highlight")) {
      const std::string flag = h->get("flag").value_or("");
      if (flag == "manual") byHand.insert(h->get("image").value_or(""));
      if (flag == "manual" || !isUsedHighlight(flag) || !h->get("confidence")) continue;
      try {
        const double v = h->number("confidence");
        const std::string id = h->get("image").value_or("");
        const auto it = confidence.find(id);
        confidence[id] = it == confidence.end() ? v : std::min(it->second, v);
      } catch (const Error&) {
        // not a number: shown as unknown
      }
    }
  std::vector<LightPoint> out;
  if (!lightResult) return out;
  for (const carrier::DataItem* l : lightResult->itemsOf("light")) {
    LightPoint p;
    const std::string id = l->get("image").value_or("");
    const carrier::FileRecord* f = c.findFile(id);
    p.image = f ? f->path : id;
    try {
      if (l->get("elevationDeg") && l->get("azimuthDeg")) {
        p.elevationDeg = l->number("elevationDeg");
        p.azimuthDeg = l->number("azimuthDeg");
      } else {  // angles from the direction
        const double x = l->number("x"), y = l->number("y"), z = l->number("z");
        const double n = std::sqrt(x * x + y * y + z * z);
        if (!(n > 0)) continue;
        p.elevationDeg = std::asin(std::clamp(z / n, -1.0, 1.0)) * 180 / kPi;
        p.azimuthDeg = std::atan2(y, x) * 180 / kPi;
      }
    } catch (const Error&) {
      continue;  // a light that is not numbers cannot be plotted
    }
    if (l->get("uncertaintyDegrees")) {
      try {
        p.uncertaintyDeg = l->number("uncertaintyDegrees");
      } catch (const Error&) {
        // not a number: shown as unknown
      }
    }
    if (const auto it = rmse.find(id); it != rmse.end()) p.rmse = it->second;
    if (const auto it = confidence.find(id); it != confidence.end()) p.highlightConfidence = it->second;
    p.highlightByHand = byHand.count(id) > 0;
    out.push_back(p);
  }
  return out;
}

namespace {

// Where the lights were, when any was placed (nearLight, docs/hrti-math.md "Near lights").
std::string nearLightsParagraph(const carrier::Carrier& c) {
  const carrier::Result* r = c.lastResultWith("light");
  if (!r) return "";
  std::vector<double> distances;
  std::map<std::string, int> bySource;
  for (const carrier::DataItem* p : r->itemsOf("nearLight")) {
    try {
      distances.push_back(p->number("distance"));
    } catch (const Error&) {
      continue;
    }
    ++bySource[p->get("source").value_or("")];
  }
  if (distances.empty()) return "";
  std::sort(distances.begin(), distances.end());
  const auto words = [](const std::string& source) {
    return source == "spheres"           ? std::string("by the two spheres")
           : source == "stated-distance" ? std::string("at the stated distance")
           : source == "spheres-median"  ? std::string("at the median distance of those the spheres placed")
                                         : source;
  };
  std::string how;
  for (const auto& [source, n] : bySource) how += (how.empty() ? "" : ", ") + std::to_string(n) + " " + words(source);
  std::ostringstream s;
  s << "<p>" << distances.size() << " of the lights were placed (" << escapeHtml(how) << "), "
    << displayNumber(distances.front(), 2) << " to " << displayNumber(distances.back(), 2)
    << " frame widths from the frame's centre: the fits give each pixel its own light direction and "
       "bring its values to the light the frame's centre had (inverse square). The directions shown "
       "are from the frame's centre.</p>";
  return s.str();
}

}  // namespace

std::string lightsSection(const carrier::Carrier& c, const std::vector<LightPoint>& lights,
                          const Coverage& coverage, const std::string& fitLabel) {
  std::ostringstream s;
  s << "<section id=\"lights\"><h2>Light directions</h2>";
  if (lights.empty()) {
    s << "<p>This carrier records no light directions (the light estimation did not run or "
         "failed; see the provenance below).</p></section>";
    return s.str();
  }
  s << "<div class=\"plot\">" << hemisphereSvg(lights, coverage, priorLightPoints(c)) << "<div><p>" << lights.size()
    << " light" << (lights.size() == 1 ? "" : "s") << " seen from the camera: the centre is a light "
       "on the camera's axis, the rim is grazing light; azimuth runs from \u2212180\u00b0 to "
       "180\u00b0: 0\u00b0 to the right of the image, 90\u00b0 at the top, \u221290\u00b0 at the bottom; the "
       "blue rings are elevations. Elevation from "
    << displayNumber(coverage.lowestElevationDeg, 1) << "\u00b0 to "
    << displayNumber(coverage.highestElevationDeg, 1) << "\u00b0. The dashed ring is "
    << displayNumber(kRakingElevationDeg, 0) << "\u00b0 elevation.</p>";
  s << "<p>" << (fitLabel.empty() ? std::string("No fit recorded residuals: points are grey.")
                                   : "Colour: the residual (RMSE) of " + escapeHtml(fitLabel) +
                                         " on each image, dark = small, yellow = large.")
    << "</p>";
  if (coverage.sentences().empty()) {
    s << "<p class=\"ok\">No gap in coverage: lights below " << displayNumber(kRakingElevationDeg, 0)
      << "\u00b0 and above " << displayNumber(kHighElevationDeg, 0)
      << "\u00b0, and no azimuth sector wider than " << displayNumber(kMaxAzimuthGapDeg, 0)
      << "\u00b0 without light.</p>";
  } else {
    s << "<h3>Gaps in coverage</h3><ul class=\"gaps\">";
    for (const std::string& g : coverage.sentences()) s << "<li>" << escapeHtml(g) << "</li>";
    s << "</ul>";
  }
  const bool anyDoubtful = std::any_of(lights.begin(), lights.end(), [](const LightPoint& l) {
    return l.highlightConfidence && *l.highlightConfidence < kDoubtfulConfidence;
  });
  if (anyDoubtful)
    s << "<p class=\"warning\">A red ring marks a light measured from a highlight of confidence below "
      << displayNumber(kDoubtfulConfidence, 1) << ": check it on the highlight overview.</p>";
  const bool anyBound = std::any_of(lights.begin(), lights.end(), [](const LightPoint& l) { return l.uncertaintyDeg; });
  if (anyBound)
    s << "<p>Each light is within its uncertainty of the true direction, 95 times in 100: the column "
         "\u00b1\u00b0 below (from its highlight, its sphere's circle and, with several spheres, their "
         "disagreement); on the plot, a dashed ring where it is wider than the light's dot (3.6\u00b0).</p>";
  s << nearLightsParagraph(c);
  s << "</div></div><details><summary>Every light</summary><table><tr><th>image</th>"
       "<th>elevation \u00b0</th><th>azimuth \u00b0</th><th>\u00b1\u00b0 (95 %)</th><th>residual</th>"
       "<th>highlight confidence</th></tr>";
  for (const LightPoint& l : lights)
    s << "<tr><td><code>" << escapeHtml(l.image) << "</code></td><td class=\"num\">"
      << displayNumber(l.elevationDeg, 1) << "</td><td class=\"num\">" << displayNumber(l.azimuthDeg, 1)
      << "</td><td class=\"num\">" << (l.uncertaintyDeg ? displayNumber(*l.uncertaintyDeg, 1) : "-")
      << "</td><td class=\"num\">" << (l.rmse ? displayNumber(*l.rmse, 2) : "-") << "</td><td class=\"num\">"
      << highlightConfidenceText(l) << "</td></tr>";
  s << "</table></details></section>";
  return s.str();
}

}  // namespace surrogate::report
