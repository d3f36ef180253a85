// The report's "Audit of prior work" section and the prior lights of its hemisphere plot, from
// the carrier's Audit result.
#include <algorithm>
#include <cmath>
#include <map>
#include <sstream>

#include "audit/recorded.h"
#include "core/error.h"
#include "report/embed.h"
#include "report/html.h"
#include "report/sections.h"

namespace surrogate::report {

namespace {

constexpr double kPi = 3.14159265358979323846;
// The difference pictures are embedded at their own size up to this side (a click shows them
// at it, the page at the content column's width): their legend's text needs the pixels.
constexpr int kDifferenceMaxSide = 4000;

double elevationOf(const audit::Light& l) { return std::asin(std::clamp(l[2], -1.0, 1.0)) * 180 / kPi; }
double azimuthOf(const audit::Light& l) { return std::atan2(l[1], l[0]) * 180 / kPi; }

// The prior's error at each photograph where it was rendered, on the hemisphere: the lights its
// errors were recorded with (Audit 5), else those of the light comparison.
std::string errorPlot(const audit::AuditReport& report, const audit::ModelCheck& m, std::size_t index) {
  std::map<std::string, audit::Light> comparison;
  for (const audit::LightComparison& l : report.lights)
    if (l.file == m.lightFile)
      for (const audit::ImageAngle& a : l.angles) comparison.emplace(a.image, a.prior);
  std::vector<ErrorPoint> points;
  for (const audit::ImageError& e : m.prior.images) {
    const auto found = comparison.find(e.image);
    if (!e.light && found == comparison.end()) continue;
    const audit::Light l = e.light ? *e.light : found->second;
    ErrorPoint p;
    p.image = e.image;
    p.elevationDeg = elevationOf(l);
    p.azimuthDeg = azimuthOf(l);
    p.psnr = e.psnr;
    p.rmse = e.rmse;
    for (const audit::DifferenceImage& d : m.differences) p.pictured = p.pictured || d.image == e.image;
    points.push_back(p);
  }
  if (points.empty()) return "";
  std::ostringstream s;
  s << "<div class=\"plot\">" << errorHemisphereSvg(points, "prior-errors-" + std::to_string(index + 1))
    << "<div><p>The prior model's error at each photograph, drawn at the prior light it was rendered at "
       "(the projection of the light plot above): colour is the PSNR of the prior's rendering against the "
       "photograph, yellow for the lowest (the largest error, here "
    << displayNumber(m.prior.worstPsnr, 2) << " dB at <code>" << escapeHtml(m.prior.worstImage)
    << "</code>), dark for the highest. Where the yellow points gather, the prior fails: a region of wrong "
       "lights, or lights its basis cannot follow. Ringed: the photographs of the difference images below."
       "</p></div></div>";
  return s.str();
}

// A difference picture, as large as the content column; a click shows it at its own size.
std::string differenceFigure(const carrier::Carrier& c, const ReportSource& source, const audit::DifferenceImage& d,
                             int* embedded) {
  std::ostringstream s;
  const std::string path = d.file.generic_string();
  const carrier::FileRecord* f = c.findFileByPath(path);
  const std::optional<std::string> bytes = f ? source.read(f->path) : std::nullopt;
  const std::optional<EmbeddedPicture> p = bytes ? embedPicture(*bytes, kDifferenceMaxSide) : std::nullopt;
  if (!p) {
    s << "<p class=\"bad\">" << escapeHtml(path) << ": "
      << (bytes ? "not a readable picture" : "not found in this package or capture") << "</p>";
    return s.str();
  }
  ++*embedded;
  const std::string what = d.fullScale > 0
      ? std::string(d.worst ? "At the worst image: " : "At a photograph asked for: ") + d.description
      : "Difference: " + d.description;  // Audit before version 5: 128 + difference, mid-grey
  s << "<figure class=\"difference\"><img src=\"" << p->dataUri << "\" width=\"" << p->width << "\" height=\""
    << p->height << "\" alt=\"" << escapeHtml(what) << "\" title=\"Click to see it at full size\"><figcaption>"
    << escapeHtml(what) << ". \u2014 <code>" << escapeHtml(path) << "</code> (" << p->originalWidth << "\u00d7"
    << p->originalHeight << (p->width != p->originalWidth ? ", shown at " + std::to_string(p->width) + "\u00d7" +
                                                                std::to_string(p->height) : std::string())
    << "; click the picture to see it at full size)</figcaption></figure>";
  return s.str();
}

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
       "mark its lights, red when farther from Surrogate's than both the threshold "
    << displayNumber(l.thresholdDegrees, 1) << "\u00b0 and the two lights' combined uncertainty.</p>";
  if (l.aboveThreshold.empty()) {
    s << "<p class=\"ok\">No light differs";
    if (const audit::ImageAngle* largest = l.largest())
      s << " (largest " << escapeHtml(audit::lightJudgement(*largest, l.thresholdDegrees)) << ")";
    s << ".</p>";
  } else {
    s << "<table class=\"audit-lights\"><tr><th>image</th><th>angle to Surrogate's light \u00b0</th>"
         "<th>combined uncertainty \u00b0</th><th>judged</th></tr>";
    for (const audit::ImageAngle& a : l.aboveThreshold)
      s << "<tr><td><code>" << escapeHtml(a.image) << "</code></td><td class=\"num\">"
        << displayNumber(a.degrees, 1) << "</td><td class=\"num\">" << displayNumber(a.combinedDegrees(), 1)
        << "</td><td>" << escapeHtml(audit::lightJudgement(a, l.thresholdDegrees)) << "</td></tr>";
    s << "</table>";
  }
  if (!l.onlyInPrior.empty() || !l.onlyInSurrogate.empty())
    s << "<p class=\"warning\">" << l.onlyInPrior.size() << " line(s) of the file name no photograph; "
      << l.onlyInSurrogate.size() << " photograph(s) have no prior light.</p>";
  return s.str();
}

std::string modelPart(const carrier::Carrier& c, const ReportSource& source, const audit::AuditReport& report,
                      std::size_t index, int* embedded) {
  const audit::ModelCheck& m = report.models[index];
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
  s << errorPlot(report, m, index);
  if (!m.differences.empty()) {
    s << "<div class=\"difference-images\">";
    for (const audit::DifferenceImage& d : m.differences) s << differenceFigure(c, source, d, embedded);
    s << "</div>";
  }
  return s.str();
}

}  // namespace

std::string auditSection(const carrier::Carrier& c, const ReportSource& source, int* picturesEmbedded) {
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
  for (std::size_t i = 0; i < report.models.size(); ++i) s << modelPart(c, source, report, i, picturesEmbedded);
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
      p.elevationDeg = elevationOf(a.prior);
      p.azimuthDeg = azimuthOf(a.prior);
      p.angleDeg = a.degrees;
      p.aboveThreshold = a.differs(l.thresholdDegrees);
      out.push_back(p);
    }
  return out;
}

}  // namespace surrogate::report
