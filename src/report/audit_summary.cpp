// The report's first card when the capture holds an audit: the verdict in parts
// (audit::summarise), and where the evidence audited came from (carrier::Header::audited).
#include <sstream>

#include "audit/audit.h"
#include "audit/recorded.h"
#include "core/error.h"
#include "report/html.h"
#include "report/sections.h"

namespace surrogate::report {

namespace {

const char* stateClass(audit::VerdictPart::State state) {
  switch (state) {
    case audit::VerdictPart::State::Reproduced: return "ok";
    case audit::VerdictPart::State::Differs: return "bad";
    case audit::VerdictPart::State::CannotTell: return "warning";
  }
  return "";
}

std::string evidenceLine(const carrier::Carrier& c) {
  if (!c.header.audited) return "";
  const carrier::AuditedSource& a = *c.header.audited;
  std::ostringstream s;
  s << "<p class=\"note\">The work audited: " << a.files.size() << " files copied byte for byte from the "
    << escapeHtml(a.kind) << " <code>" << escapeHtml(a.source) << "</code> on " << escapeHtml(a.copied);
  if (!a.packageSha256.empty()) s << " (the package's SHA-256 <code>" << escapeHtml(a.packageSha256) << "</code>)";
  s << "; nothing was written into it. Each copy's path, size and SHA-256 are in the carrier's header.</p>";
  return s.str();
}

}  // namespace

std::string auditSummarySection(const carrier::Carrier& c) {
  const carrier::Result* r = audit::auditResult(c);
  if (!r) return "";
  audit::AuditReport report;
  try {
    report = audit::recordedAudit(c, *r);
  } catch (const Error&) {
    return "";  // the audit section says why
  }
  const bool reproduced = audit::auditReproduced(report);
  std::ostringstream s;
  s << "<section id=\"audit-summary\"><h2>Audit: <span class=\"" << (reproduced ? "ok" : "bad") << "\">"
    << (reproduced ? "reproduced" : report.verdicts.empty() ? "cannot tell" : "not reproduced") << "</span></h2>";
  for (const audit::VerdictSummary& v : audit::summarise(report)) {
    s << "<div class=\"fact\"><h3><code>" << escapeHtml(v.subject) << "</code>: <span class=\""
      << (v.reproduced ? "ok" : "bad") << "\">" << (v.reproduced ? "reproduced" : "not reproduced")
      << "</span> (threshold " << displayNumber(v.thresholdDegrees, 1)
      << "\u00b0)</h3><table class=\"audit-verdict\"><tr><th>part</th><th>state</th><th>figure</th><th>likely cause</th></tr>";
    for (const audit::VerdictPart& p : v.parts)
      s << "<tr><td>" << escapeHtml(p.name) << "</td><td class=\"" << stateClass(p.state) << "\"><b>"
        << audit::stateName(p.state) << "</b></td><td>" << escapeHtml(p.figure) << "</td><td>" << escapeHtml(p.cause)
        << "</td></tr>";
    s << "</table></div>";
  }
  for (const audit::AuditReport::PriorLog& l : report.logs) {
    s << "<div class=\"fact\"><h3>Prior log <code>" << escapeHtml(l.file.generic_string()) << "</code>"
      << (l.records.empty() ? "" : " (" + escapeHtml(l.records.front()) + ")") << "</h3>";
    if (l.discrepancies.empty()) s << "<p class=\"ok\">It agrees with the photographs audited.</p>";
    else {
      s << "<p class=\"warning\">Where it differs from the capture audited:</p><ul>";
      for (const std::string& d : l.discrepancies) s << "<li>" << escapeHtml(d) << "</li>";
      s << "</ul>";
    }
    s << "<details><summary>What it records of the processing</summary><ul>";
    for (std::size_t i = 1; i < l.records.size(); ++i) s << "<li>" << escapeHtml(l.records[i]) << "</li>";
    s << "</ul></details></div>";
  }
  for (const auto& n : report.notAudited)
    s << "<p class=\"warning\"><code>" << escapeHtml(n.file.generic_string()) << "</code> cannot be read: "
      << escapeHtml(n.reason) << ".</p>";
  s << evidenceLine(c) << "<p class=\"note\">The figures, the difference images and the lights are in "
    << "<a href=\"#audit\">Audit of prior work</a> below.</p></section>";
  return s.str();
}

}  // namespace surrogate::report
