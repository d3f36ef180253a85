// The report's "Audit of prior work" section and the prior lights of its hemisphere plot, from
// the carrier's Audit result.
#include <algorithm>
#include <cmath>
#include <map>
#include <sstream>

#include "audit/recorded.h"
#include "core/error.h"
#include "report/html.h"
#include "report/sections.h"

namespace surrogate::report {

namespace {

constexpr double kPi = 3.14159265358979323846;

std::string errorsRow(const std::string& label, const audit::ModelErrors& e) {
  std::ostringstream s;
  s << "<tr><td>" << escapeHtml(label) << "</td>";
  if (!e.computed) {
    s << "<td colspan=\"4\" class=\"note\">not computed: " << escapeHtml(e.note) << "</td></tr>";
    return s.str();
  }
  s << "<td class=\"num\">" << displayNumber(e.psnr, 2) << "</td><td class=\"num\">" << displayNumber(e.rmse, 2)
    << "</td><td class=\"num\">" << displayNumber(e.medianPsnr, 2) << "</td><td class=\"num\">"
    << displayNumber(e.worstPsnr, 2) << " (<code>" << escapeHtml(e.worstImage) << "</code>)</td></tr>";
  return s.str();
}

std::string lightsPart(const audit::LightComparison& l) {
  std::ostringstream s;
  s << "<h3>Prior light file <code>" << escapeHtml(l.file.generic_string()) << "</code></h3><p>"
    << l.angles.size() << " images compared with Surrogate's lights: median "
    << displayNumber(l.medianDegrees, 1) << "\u00b0, 95th percentile " << displayNumber(l.p95Degrees, 1)
    << "\u00b0, largest " << displayNumber(l.maxDegrees, 1) << "\u00b0. Crosses on the light plot above "
       "mark its lights, red when more than " << displayNumber(l.thresholdDegrees, 1)
    << "\u00b0 from Surrogate's.</p>";
  if (l.aboveThreshold.empty()) {
    s << "<p class=\"ok\">No image above " << displayNumber(l.thresholdDegrees, 1) << "\u00b0.</p>";
  } else {
    s << "<table class=\"audit-lights\"><tr><th>image</th><th>angle to Surrogate's light \u00b0</th></tr>";
    for (const audit::ImageAngle& a : l.aboveThreshold)
      s << "<tr><td><code>" << escapeHtml(a.image) << "</code></td><td class=\"num\">"
        << displayNumber(a.degrees, 1) << "</td></tr>";
    s << "</table>";
  }
  if (!l.onlyInPrior.empty() || !l.onlyInSurrogate.empty())
    s << "<p class=\"warning\">" << l.onlyInPrior.size() << " line(s) of the file name no photograph; "
      << l.onlyInSurrogate.size() << " photograph(s) have no prior light.</p>";
  return s.str();
}

std::string modelPart(const carrier::Carrier& c, const audit::ModelCheck& m,
                      const std::function<std::string(const carrier::FileRecord&, const std::string&)>& figure) {
  std::ostringstream s;
  s << "<h3>Prior model <code>" << escapeHtml(m.file.generic_string()) << "</code></h3><p>"
    << escapeHtml(m.basis) << ", rendered at the lights of <code>"
    << escapeHtml(m.lightFile.empty() ? std::string("(none)") : m.lightFile.generic_string()) << "</code>; "
    << escapeHtml(m.size.describe()) << ". Error on the Rec. 709 luminance of the " << escapeHtml(m.values)
    << " photographs, 0..255:</p><table class=\"audit-psnr\"><tr><th>model</th><th>PSNR (dB)</th>"
       "<th>RMSE</th><th>median PSNR</th><th>worst PSNR</th></tr>"
    << errorsRow("prior model, prior lights", m.prior)
    << errorsRow("Surrogate's fit, prior lights", m.refitPriorLights)
    << errorsRow("Surrogate's fit, Surrogate's lights", m.refitSurrogateLights) << "</table>";
  std::string clipped;
  for (const audit::PlaneCheck& p : m.quantisation.planes)
    if (p.clamped) clipped += (clipped.empty() ? "" : ", ") + p.plane;
  s << "<p class=\"" << (clipped.empty() ? "ok" : "bad") << "\">Quantisation: "
    << (clipped.empty() ? std::string("no clipped coefficient plane") : "clipped planes " + escapeHtml(clipped))
    << ".</p>";
  if (m.colour.measured)
    s << "<p>Tone of the prior against the photographs: gain " << displayNumber(m.colour.gain, 3) << ", gamma "
      << displayNumber(m.colour.gamma, 3) << (m.colour.differs ? " (differs)" : "") << ".</p>";
  if (!m.differenceImage.empty()) {
    if (const carrier::FileRecord* f = c.findFileByPath(m.differenceImage.generic_string()))
      s << "<div class=\"gallery\">" << figure(*f, "Difference: " + m.differenceDescription) << "</div>";
  }
  return s.str();
}

}  // namespace

std::string auditSection(const carrier::Carrier& c,
                         const std::function<std::string(const carrier::FileRecord&, const std::string&)>& figure) {
  const carrier::Result* r = audit::auditResult(c);
  if (!r) return "";
  std::ostringstream s;
  s << "<section id=\"audit\"><h2>Audit of prior work</h2>";
  audit::AuditReport report;
  try {
    report = audit::recordedAudit(c, *r);
  } catch (const Error& e) {
    s << "<p class=\"bad\">The recorded audit cannot be read: " << escapeHtml(e.text()) << "</p></section>";
    return s.str();
  }
  s << "<p>Step " << escapeHtml(r->step) << " compared the prior work another tool left in the capture "
       "with Surrogate's lights and fit (threshold " << displayNumber(report.thresholdDegrees, 1)
    << "\u00b0).</p>";
  for (const audit::Verdict& v : report.verdicts)
    s << "<p class=\"verdict " << (v.reproduced ? "ok" : "bad") << "\"><b><code>"
      << escapeHtml((v.model.empty() ? v.lightFile : v.model).generic_string()) << "</code></b>: "
      << escapeHtml(v.sentence) << "</p>";
  for (const audit::LightComparison& l : report.lights) s << lightsPart(l);
  for (const audit::ModelCheck& m : report.models) s << modelPart(c, m, figure);
  for (const auto& n : report.notAudited)
    s << "<p class=\"warning\">Not audited: <code>" << escapeHtml(n.file.generic_string()) << "</code> ("
      << escapeHtml(n.reason) << ").</p>";
  s << "</section>";
  return s.str();
}

std::vector<PriorLightPoint> priorLightPoints(const carrier::Carrier& c) {
  std::vector<PriorLightPoint> out;
  const carrier::Result* r = audit::auditResult(c);
  if (!r) return out;
  audit::AuditReport report;
  try {
    report = audit::recordedAudit(c, *r);
  } catch (const Error&) {
    return out;  // the section says why
  }
  // Photographs by file name, to the path the plot knows them by.
  std::map<std::string, std::string> pathOfName;
  for (const carrier::FileRecord& f : c.files)
    pathOfName.emplace(std::filesystem::u8path(f.path).filename().u8string(), f.path);
  for (const audit::LightComparison& l : report.lights)
    for (const audit::ImageAngle& a : l.angles) {
      PriorLightPoint p;
      const auto it = pathOfName.find(a.image);
      p.image = it == pathOfName.end() ? a.image : it->second;
      p.file = l.file.generic_string();
      p.elevationDeg = std::asin(std::clamp(a.prior[2], -1.0, 1.0)) * 180 / kPi;
      p.azimuthDeg = std::atan2(a.prior[1], a.prior[0]) * 180 / kPi;
      p.angleDeg = a.degrees;
      p.aboveThreshold = a.degrees > l.thresholdDegrees;
      out.push_back(p);
    }
  return out;
}

}  // namespace surrogate::report
