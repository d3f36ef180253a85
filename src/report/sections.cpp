#include "report/sections.h"

#include <map>
#include <sstream>

#include "meta/camera_text.h"
#include "report/html.h"

namespace surrogate::report {

namespace {

std::string seconds(double s) {
  if (s < 1) return displayNumber(s * 1000, 0) + " ms";
  if (s < 120) return displayNumber(s, 1) + " s";
  return displayNumber(s / 60, 1) + " min";
}

std::string attribute(const carrier::FileRecord& f, const std::string& name) {
  for (const auto& [k, v] : f.camera)
    if (k == name) return v;
  return "";
}

std::string bytes(std::uint64_t n) {
  if (n < 1024) return std::to_string(n) + " B";
  if (n < 1024 * 1024) return displayNumber(n / 1024.0, 1) + " KiB";
  if (n < 1024ull * 1024 * 1024) return displayNumber(n / (1024.0 * 1024.0), 1) + " MiB";
  return displayNumber(n / (1024.0 * 1024.0 * 1024.0), 1) + " GiB";
}

}  // namespace

std::string provenanceSection(const carrier::Carrier& c) {
  std::ostringstream s;
  s << "<section id=\"provenance\"><h2>Provenance</h2>";
  const carrier::Machine& m = c.header.machine;
  s << "<p>Run on <b>" << escapeHtml(m.hostname) << "</b> (" << escapeHtml(m.os) << ", "
    << escapeHtml(m.architecture) << ", " << escapeHtml(m.cpu) << ", " << m.cores << " cores, "
    << bytes(m.memoryBytes) << ").</p><table><tr><th>software</th><th>version</th><th>role</th></tr>";
  for (const carrier::Software& sw : c.header.software)
    s << "<tr><td>" << escapeHtml(sw.name) << "</td><td>" << escapeHtml(sw.version) << "</td><td>"
      << escapeHtml(sw.role) << "</td></tr>";
  s << "</table>";
  if (!c.header.meta.empty()) {
    s << "<table><tr><th>metadata</th><th>value</th></tr>";
    for (const auto& [k, v] : c.header.meta)
      s << "<tr><td>" << escapeHtml(k) << "</td><td>" << escapeHtml(v) << "</td></tr>";
    s << "</table>";
  }

  s << "<h3>Steps</h3><ol class=\"timeline\">";
  for (const carrier::Step& step : c.process) {
    const carrier::Result* r = c.findResult(step.id);
    const std::string status = r ? r->status : "not run";
    s << "<li class=\"step " << (status == "completed" ? "completed" : "failed") << "\" data-step=\""
      << escapeHtml(step.id) << "\"><div class=\"step-head\">" << escapeHtml(stepTitle(step))
      << " <span class=\"note\">(step " << escapeHtml(step.id) << ", " << escapeHtml(step.component) << " v"
      << escapeHtml(step.version);
    if (!step.algorithm.empty()) s << ", " << escapeHtml(step.algorithm);
    s << ")</span>";
    s << " \u2014 <span class=\"" << (status == "completed" ? "ok" : "bad") << "\">" << escapeHtml(status)
      << "</span></div>";
    if (r)
      s << "<div class=\"note\">started " << escapeHtml(r->started) << ", took " << seconds(r->seconds)
        << "</div>";
    if (!step.description.empty()) s << "<div>" << escapeHtml(step.description) << "</div>";
    if (!step.params.empty()) {
      s << "<details><summary>" << step.params.size() << " parameter"
        << (step.params.size() == 1 ? "" : "s") << "</summary><table>";
      for (const carrier::Param& p : step.params)
        s << "<tr><td>" << escapeHtml(p.name) << "</td><td><code>" << escapeHtml(p.value)
          << "</code></td></tr>";
      s << "</table></details>";
    }
    for (const carrier::Intervention& i : step.interventions) {
      s << "<div class=\"intervention\"><b>Human intervention: " << escapeHtml(i.kind) << "</b> on <code>"
        << escapeHtml(i.target) << "</code>";
      if (!i.value.empty()) s << ", value <code>" << escapeHtml(i.value) << "</code>";
      s << "<br>by " << escapeHtml(i.who.empty() ? std::string("(not recorded)") : i.who);
      if (!i.time.empty()) s << " at " << escapeHtml(i.time);
      s << "<br>reason: " << escapeHtml(i.reason) << "</div>";
    }
    std::ostringstream notable, other;
    int others = 0;
    for (const carrier::LogEntry& e : c.log) {
      if (e.step != step.id) continue;
      const bool important = e.level == "warning" || e.level == "error";
      std::ostringstream& out = important ? notable : other;
      out << "<li class=\"" << (e.level == "error" ? "bad" : e.level == "warning" ? "warning" : "")
          << "\"><span class=\"note\">" << escapeHtml(e.time) << " " << escapeHtml(e.level) << "</span> "
          << escapeHtml(e.text);
      if (!e.who.empty()) out << " <span class=\"note\">(" << escapeHtml(e.who) << ")</span>";
      out << "</li>";
      others += !important;
    }
    if (!notable.str().empty()) s << "<ul>" << notable.str() << "</ul>";
    if (others > 0)
      s << "<details><summary>" << others << " log entr" << (others == 1 ? "y" : "ies")
        << "</summary><ul>" << other.str() << "</ul></details>";
    s << "</li>";
  }
  s << "</ol>";
  std::ostringstream general;
  for (const carrier::LogEntry& e : c.log) {
    bool known = false;
    for (const carrier::Step& step : c.process) known = known || step.id == e.step;
    if (!known)
      general << "<li><span class=\"note\">" << escapeHtml(e.time) << " " << escapeHtml(e.level)
              << "</span> " << escapeHtml(e.text) << "</li>";
  }
  if (!general.str().empty()) s << "<h3>Other log entries</h3><ul>" << general.str() << "</ul>";
  s << "</section>";
  return s.str();
}

std::string takenText(const std::string& exifDateTime) { return meta::dateTimeText(exifDateTime, std::nullopt); }

std::string cameraSection(const carrier::Carrier& c) {
  // Distinct values of each EXIF field over the originals (exports when there are none).
  bool haveOriginals = false;
  for (const carrier::FileRecord& f : c.files) haveOriginals = haveOriginals || f.role == "original";
  const char* fields[][2] = {{"make", "make"}, {"model", "model"}, {"serial", "body serial"},
                             {"lens", "lens"}, {"focalLengthMm", "focal length (mm)"},
                             {"fNumber", "f-number"}, {"exposureTime", "exposure"}, {"iso", "ISO"}};
  std::ostringstream rows;
  std::string firstDate, lastDate;
  for (const auto& field : fields) {
    std::map<std::string, int> counts;
    for (const carrier::FileRecord& f : c.files) {
      if (f.role != (haveOriginals ? "original" : "export")) continue;
      const std::string v = attribute(f, field[0]);
      if (!v.empty()) ++counts[v];
    }
    if (counts.empty()) continue;
    rows << "<tr><td>" << field[1] << "</td><td>";
    bool first = true;
    for (const auto& [v, n] : counts) {
      rows << (first ? "" : "; ") << escapeHtml(v);
      if (counts.size() > 1) rows << " <span class=\"note\">(" << n << " files)</span>";
      first = false;
    }
    if (counts.size() > 1) rows << " <span class=\"warning\">varies between shots</span>";
    rows << "</td></tr>";
  }
  for (const carrier::FileRecord& f : c.files) {
    const std::string d = attribute(f, "dateTimeOriginal");
    if (d.empty()) continue;
    if (firstDate.empty() || d < firstDate) firstDate = d;
    if (lastDate.empty() || d > lastDate) lastDate = d;
  }
  if (!firstDate.empty())
    rows << "<tr><td>taken</td><td>" << escapeHtml(takenText(firstDate))
         << (lastDate != firstDate ? " to " + escapeHtml(takenText(lastDate)) : std::string()) << "</td></tr>";
  std::ostringstream s;
  s << "<section id=\"camera\"><h2>Camera and lens</h2>";
  if (rows.str().empty())
    s << "<p>The images carry no EXIF camera or lens information.</p>";
  else
    s << "<p class=\"note\">From the EXIF of the " << (haveOriginals ? "originals" : "exports")
      << ".</p><table>" << rows.str() << "</table>";
  s << "</section>";
  return s.str();
}

std::string verificationSection(const std::optional<std::vector<VerificationCheck>>& checks) {
  std::ostringstream s;
  s << "<section id=\"verification\"><h2>Verification</h2>";
  if (!checks) {
    s << "<p class=\"note\">No verification was run for this report. <code>surrogate verify PACKAGE</code> "
         "checks a package's fixity and schemas, and re-executes its steps with --reexecute.</p>";
  } else if (checks->empty()) {
    s << "<p class=\"bad\">The verifier reported no checks.</p>";
  } else {
    int failed = 0;
    for (const VerificationCheck& v : *checks) failed += !v.passed;
    s << "<p class=\"" << (failed ? "bad" : "ok") << "\">"
      << (failed ? std::to_string(failed) + " of " + std::to_string(checks->size()) + " checks failed."
                 : "All " + std::to_string(checks->size()) + " checks passed.")
      << "</p><table><tr><th>check</th><th>result</th><th>detail</th></tr>";
    for (const VerificationCheck& v : *checks)
      s << "<tr class=\"check\"><td>" << escapeHtml(v.name) << "</td><td class=\""
        << (v.passed ? "ok\">passed" : "bad\">FAILED") << "</td><td>" << escapeHtml(v.detail) << "</td></tr>";
    s << "</table>";
  }
  s << "</section>";
  return s.str();
}

std::string filesSection(const carrier::Carrier& c) {
  std::map<std::string, std::pair<int, std::uint64_t>> byRole;
  for (const carrier::FileRecord& f : c.files) {
    byRole[f.role].first += 1;
    byRole[f.role].second += f.size;
  }
  std::ostringstream s;
  s << "<section id=\"files\"><h2>Files</h2><table><tr><th>role</th><th>files</th><th>size</th></tr>";
  for (const auto& [role, n] : byRole)
    s << "<tr><td>" << escapeHtml(role) << "</td><td class=\"num\">" << n.first << "</td><td class=\"num\">"
      << bytes(n.second) << "</td></tr>";
  s << "</table><details><summary>Every file with its SHA-256</summary><table><tr><th>id</th><th>path</th>"
       "<th>role</th><th>format</th><th>size</th><th>SHA-256</th></tr>";
  for (const carrier::FileRecord& f : c.files)
    s << "<tr><td>" << escapeHtml(f.id) << "</td><td><code>" << escapeHtml(f.path) << "</code>"
      << (f.unrecordedProcessing ? " <span class=\"warning\">made by other software</span>" : "")
      << "</td><td>" << escapeHtml(f.role) << "</td><td>" << escapeHtml(f.format) << "</td><td class=\"num\">"
      << f.size << "</td><td class=\"mono\">" << escapeHtml(f.sha256) << "</td></tr>";
  s << "</table></details></section>";
  return s.str();
}

namespace {

// What a check looked at, so that the same check on two fits reads as two checks: the step's
// title, which names a fit's model ("Fit: PTM (LRGB)").
std::string checkedOn(const carrier::Carrier& c, const carrier::Result& r) {
  const carrier::Step* step = c.findStep(r.step);
  return step ? stepTitle(*step) : r.step;
}

}  // namespace

std::string lightChecksTable(const carrier::Carrier& c) {
  std::ostringstream s;
  bool any = false;
  for (const carrier::Result& r : c.data)
    for (const carrier::DataItem* d : r.itemsOf("check")) {
      if (!any) s << "<h3>Checks on the lights</h3><table><tr><th>check</th><th>on</th><th>status</th><th>figures</th></tr>";
      any = true;
      const std::string status = d->get("status").value_or("");
      s << "<tr" << (status == "passed" ? "" : " class=\"warning\"") << "><td><code>"
        << escapeHtml(d->get("name").value_or("")) << "</code></td><td>" << escapeHtml(checkedOn(c, r)) << "</td><td>"
        << escapeHtml(status) << "</td><td>"
        << escapeHtml(d->get("detail").value_or("")) << "</td></tr>";
    }
  if (any)
    s << "</table><p class=\"note\">A failed check stops the run; <em>accepted</em> means someone accepted it "
         "on the record (<code>--accept NAME --reason</code>; who and why are in the provenance).</p>";
  return s.str();
}

}  // namespace surrogate::report
