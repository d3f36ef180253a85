// The report's first screen: what the object is, how it was captured, whether the package
// verified, and the figures a photographer judges a capture by (sphere count, light spread,
// fit quality); and the names people give the steps.
#include <algorithm>
#include <functional>
#include <map>
#include <sstream>

#include "core/error.h"
#include "report/explain.h"
#include "report/html.h"
#include "report/sections.h"

namespace surrogate::report {

namespace {

std::string cameraAttribute(const carrier::FileRecord& f, const std::string& name) {
  for (const auto& [k, v] : f.camera)
    if (k == name) return v;
  return "";
}

// The originals' records, or the exports' when the capture has no originals (a JPEG-only one).
std::vector<const carrier::FileRecord*> sourceImages(const carrier::Carrier& c) {
  std::vector<const carrier::FileRecord*> originals, exports;
  for (const carrier::FileRecord& f : c.files) {
    if (f.role == "original") originals.push_back(&f);
    if (f.role == "export") exports.push_back(&f);
  }
  return originals.empty() ? exports : originals;
}

// The value most files share ("" when none records it), with "(and others)" when they differ.
std::string commonValue(const std::vector<const carrier::FileRecord*>& files,
                        const std::function<std::string(const carrier::FileRecord&)>& valueOf) {
  std::map<std::string, int> counts;
  for (const carrier::FileRecord* f : files)
    if (const std::string v = valueOf(*f); !v.empty()) ++counts[v];
  if (counts.empty()) return "";
  const auto most = std::max_element(counts.begin(), counts.end(),
                                     [](const auto& a, const auto& b) { return a.second < b.second; });
  return most->first + (counts.size() > 1 ? " (and others)" : "");
}

// "Canon EOS 5D": the model alone when it already starts with the make.
std::string cameraName(const carrier::FileRecord& f) {
  const std::string make = cameraAttribute(f, "make"), model = cameraAttribute(f, "model");
  if (model.empty()) return make;
  if (make.empty() || model.rfind(make, 0) == 0) return model;
  return make + " " + model;
}

std::string dateRange(const std::vector<const carrier::FileRecord*>& files) {
  std::string first, last;
  for (const carrier::FileRecord* f : files) {
    const std::string d = cameraAttribute(*f, "dateTimeOriginal");
    if (d.empty()) continue;
    if (first.empty() || d < first) first = d;
    if (last.empty() || d > last) last = d;
  }
  if (first.empty()) return "";
  return takenText(first) + (last != first ? " to " + takenText(last) : "");
}

int processedImages(const carrier::Carrier& c) {
  int images = 0;
  for (const carrier::Result& r : c.data)
    if (!r.itemsOf("decoded").empty()) images = static_cast<int>(r.itemsOf("decoded").size());
  return images;
}

int sphereCount(const carrier::Carrier& c) {
  int spheres = 0;
  for (const carrier::Result& r : c.data) spheres = std::max(spheres, static_cast<int>(r.itemsOf("sphere").size()));
  return spheres;
}

// One line of a <dl>: the value is already HTML.
void fact(std::ostringstream& s, const std::string& term, const std::string& valueHtml) {
  if (!valueHtml.empty()) s << "<dt>" << term << "</dt><dd>" << valueHtml << "</dd>";
}

std::string objectFacts(const carrier::Carrier& c) {
  std::ostringstream s;
  s << "<div class=\"fact\"><h3>Object</h3><dl>";
  fact(s, "title", escapeHtml(c.header.title));
  for (const carrier::Creator& cr : c.header.creators)
    fact(s, escapeHtml(cr.role.empty() ? std::string("creator") : cr.role), escapeHtml(cr.name));
  fact(s, "rights", escapeHtml(c.header.rights));
  fact(s, "licence", c.header.license.empty() ? "" : "<code>" + escapeHtml(c.header.license) + "</code>");
  if (c.header.rights.empty() && c.header.license.empty())
    fact(s, "rights", "<span class=\"warning\">not recorded (--rights, --license)</span>");
  s << "</dl></div>";
  return s.str();
}

std::string captureFacts(const carrier::Carrier& c, std::size_t lights) {
  const std::vector<const carrier::FileRecord*> images = sourceImages(c);
  int excluded = 0;
  for (const carrier::Step& step : c.process) excluded += static_cast<int>(step.interventionsOfKind("exclude-image").size());
  std::ostringstream s;
  s << "<div class=\"fact\"><h3>Capture</h3><dl>";
  std::ostringstream count;
  count << images.size() << " " << (!images.empty() && images.front()->role == "export" ? "exports" : "originals")
        << ", " << processedImages(c) << " processed";
  if (excluded) count << ", <span class=\"warning\">" << excluded << " excluded by hand</span>";
  fact(s, "images", count.str());
  fact(s, "lights", std::to_string(lights));
  fact(s, "camera", escapeHtml(commonValue(images, cameraName)));
  fact(s, "lens", escapeHtml(commonValue(images, [](const carrier::FileRecord& f) { return cameraAttribute(f, "lens"); })));
  fact(s, "taken", escapeHtml(dateRange(images)));
  s << "</dl></div>";
  return s.str();
}

std::string verificationFacts(const std::optional<std::vector<VerificationCheck>>& checks) {
  std::ostringstream s;
  s << "<div class=\"fact\"><h3>Verification</h3><p>";
  if (!checks) {
    s << "<span class=\"note\">Not verified for this report (<code>surrogate verify</code>).</span>";
  } else {
    int failed = 0;
    for (const VerificationCheck& v : *checks) failed += !v.passed;
    if (checks->empty()) s << "<span class=\"bad\">The verifier reported no checks.</span>";
    else if (failed)
      s << "<span class=\"bad verdict\">FAILED</span>: " << failed << " of " << checks->size() << " checks failed.";
    else s << "<span class=\"ok verdict\">PASSED</span>: all " << checks->size() << " checks.";
  }
  s << "</p></div>";
  return s.str();
}

// "PSNR 38.2 dB" of each fit that recorded one, by step title.
std::string fitFigures(const carrier::Carrier& c) {
  std::ostringstream s;
  for (const carrier::Step& step : c.process) {
    const carrier::Result* r = c.findResult(step.id);
    if (!r) continue;
    for (const carrier::DataItem* v : r->itemsOf("value")) {
      if (v->get("name") != "psnr") continue;
      try {
        s << (s.str().empty() ? "" : "<br>") << escapeHtml(stepTitle(step)) << ": "
          << displayNumber(v->number("value"), 1) << " dB, " << judgePsnr(v->number("value"));
      } catch (const Error&) {
        // an unreadable PSNR is left out of the summary; the results table shows "-"
      }
    }
  }
  return s.str();
}

// "3 warnings", wrapped in a span of class `cls` when n > 0.
std::string counted(int n, const std::string& noun, const std::string& cls = "") {
  const std::string text = std::to_string(n) + " " + noun + (n == 1 ? "" : "s");
  return n > 0 && !cls.empty() ? "<span class=\"" + cls + "\">" + text + "</span>" : text;
}

// "elevation 15.5-74.9°; no azimuth gap > 90°", the widest gap in red when there is one.
std::string lightSpread(const Coverage& coverage) {
  double widest = 0;
  for (const AzimuthGap& g : coverage.azimuthGaps) widest = std::max(widest, g.widthDeg() == 0 ? 360 : g.widthDeg());
  const std::string elevation = "elevation " + displayNumber(coverage.lowestElevationDeg, 1) + "\u2013" +
                                displayNumber(coverage.highestElevationDeg, 1) + "\u00b0; ";
  if (coverage.azimuthGaps.empty())
    return elevation + "no azimuth gap &gt; " + displayNumber(kMaxAzimuthGapDeg, 0) + "\u00b0";
  return elevation + "<span class=\"bad\">azimuth gap of " + displayNumber(widest, 0) + "\u00b0</span>";
}

std::string keyFigures(const carrier::Carrier& c, const std::vector<LightPoint>& lights, const Coverage& coverage) {
  std::ostringstream s;
  s << "<div class=\"fact\"><h3>Key figures</h3><dl>";
  const int spheres = sphereCount(c);
  fact(s, "spheres", spheres ? std::to_string(spheres) : std::string("none (lights from a file)"));
  if (!lights.empty()) {
    fact(s, "light spread", lightSpread(coverage));
    const int gaps = static_cast<int>(coverage.sentences().size());
    fact(s, "coverage", gaps ? counted(gaps, "gap", "bad") : std::string("<span class=\"ok\">no gap</span>"));
  }
  fact(s, "fit PSNR", fitFigures(c));
  int interventions = 0, warnings = 0, errors = 0;
  for (const carrier::Step& step : c.process) interventions += static_cast<int>(step.interventions.size());
  for (const carrier::LogEntry& e : c.log) {
    warnings += e.level == "warning";
    errors += e.level == "error";
  }
  fact(s, "by hand", counted(interventions, "intervention"));
  fact(s, "log", counted(errors, "error", "bad") + ", " + counted(warnings, "warning", "warning"));
  s << "</dl></div>";
  return s.str();
}

}  // namespace

std::string stepTitle(const carrier::Step& step) {
  static const std::map<std::string, std::string> titles = {
      {"CaptureIngest", "Capture: files recorded"},
      {"ImageDecode", "Decode the images"},
      {"WhiteBalance", "White balance"},
      {"Crop", "Crop"},
      {"Resize", "Resize"},
      {"SphereDetection", "Sphere detection"},
      {"HighlightDetection", "Highlight detection"},
      {"LightDirections", "Light directions from the spheres"},
      {"LightsFromFile", "Light directions from a file"},
      {"DerivedMaps", "Normals, albedo and previews"},
      {"Audit", "Audit of prior work"},
  };
  if (step.component == "RtiFit" || step.component == "LearnedFit") return "Fit: " + modelTitle(step.param("basis", "?"));
  // One step per model: the model tells two apart.
  if (step.component == "WebCopy") return "Web copy of " + modelTitle(step.param("model", "?"));
  if (step.component == "DerivedMaps" && step.hasParam("model"))
    return "Normals, albedo and previews from " + modelTitle(step.param("model", "?"));
  const auto it = titles.find(step.component);
  return it == titles.end() ? step.component : it->second;
}

std::string modelTitle(const std::string& basis) {
  if (basis == "ptm-lrgb") return "PTM (LRGB)";
  if (basis == "ptm-rgb") return "PTM (RGB)";
  if (basis == "hsh2") return "HSH order 2";
  if (basis == "hsh3") return "HSH order 3";
  if (basis == "hsh4") return "HSH order 4";
  if (basis == "rbf") return "RBF (learned)";
  if (basis == "bln") return "Bilinear (learned)";
  return basis;
}

std::string summarySection(const carrier::Carrier& c, const std::vector<LightPoint>& lights,
                           const Coverage& coverage,
                           const std::optional<std::vector<VerificationCheck>>& checks) {
  return "<section id=\"summary\"><h2 class=\"visually-hidden\">Summary</h2><div class=\"facts\">" +
         objectFacts(c) + captureFacts(c, lights.size()) + verificationFacts(checks) +
         keyFigures(c, lights, coverage) + "</div></section>";
}

}  // namespace surrogate::report
