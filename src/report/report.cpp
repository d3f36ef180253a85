#include "report/report.h"

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <future>
#include <map>
#include <sstream>

#include "capture/capture.h"
#include "core/atomic_file.h"
#include "core/error.h"
#include "core/parallel.h"
#include "core/resident.h"
#include "core/sphere_reference.h"
#include "core/version.h"
#include "report/colour_section.h"
#include "report/embed.h"
#include "report/hemisphere.h"
#include "report/explain.h"
#include "report/html.h"
#include "report/lights_section.h"
#include "report/outputs.h"
#include "report/page_assets.h"
#include "report/relight_section.h"
#include "report/sections.h"

namespace surrogate::report {

namespace {

std::string numberOr(const carrier::DataItem& d, const char* name, int digits, const std::string& absent = "-") {
  try {
    return d.get(name) ? displayNumber(d.number(name), digits) : absent;
  } catch (const Error&) {
    return absent;
  }
}

// A highlight's confidence as the page shows it: "by hand" for one given by hand (the carrier
// records 1, which it did not earn), else the number.
std::string confidenceText(const carrier::DataItem& highlight) {
  return highlight.get("flag").value_or("") == "manual" ? std::string("by hand") : numberOr(highlight, "confidence", 2);
}

// The pictures the page shows (overlays, overviews, normals, albedo, previews), each read,
// decoded, downscaled and encoded as JPEG once (only encoded when the options hold its display
// copy). prepare() does a list of them on several threads at once: decoding the PNGs and
// encoding the JPEGs is most of the report's time, and each picture's JPEG depends on its own
// file's bytes alone, so the page is the same at any thread count. A picture not prepared is
// done when the page asks for it.
class Pictures {
 public:
  struct Picture {
    bool found = false;                      // the source holds the file
    std::optional<EmbeddedPicture> embedded;  // nullopt: not a readable picture
  };

  Pictures(const ReportSource& source, int maxSide,
           std::shared_ptr<const std::map<std::string, DisplayPicture>> displayed)
      : source_(source), maxSide_(maxSide), displayed_(std::move(displayed)) {}

  void prepare(const std::vector<std::string>& paths, int threads) {
    std::vector<std::string> todo;
    for (const std::string& p : paths)
      if (!done_.count(p) && std::find(todo.begin(), todo.end(), p) == todo.end()) todo.push_back(p);
    std::vector<Picture> made(todo.size());
    parallelFor(todo.size(), 1, threads, [&](std::size_t begin, std::size_t end) {
      for (std::size_t i = begin; i < end; ++i) made[i] = make(todo[i]);
    });
    for (std::size_t i = 0; i < todo.size(); ++i) done_.emplace(todo[i], std::move(made[i]));
  }

  Picture get(const std::string& path) const {
    const auto it = done_.find(path);
    return it != done_.end() ? it->second : make(path);
  }

 private:
  Picture make(const std::string& path) const {
    Picture p;
    if (displayed_) {
      const auto it = displayed_->find(path);
      if (it != displayed_->end() && it->second.maxSide == maxSide_) {
        p.found = true;
        p.embedded = embedPicture(it->second);
        return p;
      }
    }
    const std::optional<std::string> bytes = source_.read(path);
    p.found = bytes.has_value();
    if (bytes) p.embedded = embedPicture(*bytes, maxSide_);
    return p;
  }

  const ReportSource& source_;
  int maxSide_;
  std::shared_ptr<const std::map<std::string, DisplayPicture>> displayed_;  // may be null
  std::map<std::string, Picture> done_;
};

std::string figure(const Pictures& pictures, const carrier::FileRecord& file, const std::string& caption,
                   int* embedded) {
  std::ostringstream s;
  const Pictures::Picture picture = pictures.get(file.path);
  const std::optional<EmbeddedPicture>& p = picture.embedded;
  if (!p) {
    s << "<p class=\"bad\">" << escapeHtml(file.path) << ": "
      << (picture.found ? "not a readable picture" : "not found in this package or capture")
      << "</p>";
    return s.str();
  }
  ++*embedded;
  s << "<figure><img src=\"" << p->dataUri << "\" width=\"" << p->width << "\" height=\"" << p->height
    << "\" alt=\"" << escapeHtml(caption) << "\"><figcaption>" << escapeHtml(caption) << " \u2014 <code>"
    << escapeHtml(file.path) << "</code> (" << p->originalWidth << "\u00d7" << p->originalHeight
    << ", shown at " << p->width << "\u00d7" << p->height << ")</figcaption></figure>";
  return s.str();
}

std::string previewCaption(const std::string& path) {
  if (path.find("raking") != std::string::npos) return "Relit: raking light";
  if (path.find("top") != std::string::npos) return "Relit: light from above";
  if (path.find("specular") != std::string::npos) return "Relit: specular enhancement";
  return "Relit preview";
}

std::string detectionSection(const carrier::Carrier& c, const Pictures& pictures,
                             Report& report) {
  std::ostringstream s;
  s << "<section id=\"detection\"><h2>Sphere and highlight detection</h2>";
  std::vector<const carrier::DataItem*> spheres, highlights, flagged;
  for (const carrier::Result& r : c.data) {
    for (const carrier::DataItem* d : r.itemsOf("sphere")) spheres.push_back(d);
    for (const carrier::DataItem* d : r.itemsOf("highlight")) {
      highlights.push_back(d);
      bool doubtful = false;
      try {
        doubtful = d->get("confidence") && d->number("confidence") < kDoubtfulConfidence;
      } catch (const Error&) {
      }
      if (d->get("flag").value_or("ok") != "ok" || doubtful) flagged.push_back(d);
    }
  }
  if (spheres.empty()) {
    s << "<p>No sphere was detected or recorded (the lights may come from an .lp file).</p>";
  } else {
    s << "<table><tr><th>sphere</th><th>centre x, y (px)</th><th>radius (px)</th>"
         "<th>rim</th><th>moving highlight</th><th>source</th></tr>";
    for (const carrier::DataItem* d : spheres) {
      auto n = [&](const char* name) {
        try {
          return displayNumber(d->number(name), 2);
        } catch (const Error&) {
          return std::string("-");
        }
      };
      // A sphere given by hand was not detected: its rim and highlight scores (recorded as 1)
      // measure nothing.
      const bool byHand = d->get("source").value_or("") == "manual";
      s << "<tr><td>" << escapeHtml(sphereNumberText(d->get("index").value_or(""))) << "</td><td class=\"num\">"
        << n("cx") << ", " << n("cy") << "</td><td class=\"num\">" << n("r") << "</td><td class=\"num\">"
        << (byHand ? "by hand" : n("confidence")) << "</td><td class=\"num\">" << (byHand ? "by hand" : n("evidence"))
        << "</td><td>" << escapeHtml(byHand ? std::string("given by hand") : d->get("source").value_or("")) << "</td></tr>";
    }
    s << "</table><ul>";
    for (const carrier::DataItem* d : spheres) {
      s << "<li>Sphere " << escapeHtml(sphereNumberText(d->get("index").value_or(""))) << ": ";
      if (d->get("source").value_or("") == "manual") {
        s << "given by hand; its circle is the one given, nothing was measured.</li>";
        continue;
      }
      // Each figure the carrier records (a carrier before SphereDetection version 5 has no evidence).
      std::string said;
      try {
        said = explainRimConfidence(d->number("confidence"));
      } catch (const Error&) {
      }
      try {
        said += (said.empty() ? "" : " ") + explainEvidence(d->number("evidence"));
      } catch (const Error&) {
      }
      s << (said.empty() ? std::string("its figures are not recorded.") : said) << "</li>";
    }
    s << "</ul><p class=\"note\">Spheres are numbered from 1, as the command line names them: "
         "<code>--highlight IMAGE:sphere1=X,Y</code>, <code>--forget-sphere sphere1</code>.</p>";
  }
  s << lightChecksTable(c);
  auto imagePath = [&](const carrier::DataItem& d) {
    const carrier::FileRecord* f = c.findFile(d.get("image").value_or(""));
    return f ? f->path : d.get("image").value_or("");
  };
  if (!flagged.empty()) {
    s << "<h3>Highlights to check</h3><ul>";
    for (const carrier::DataItem* d : flagged) {
      const std::string reason = d->get("reason").value_or("");
      s << "<li class=\"warning\"><code>" << escapeHtml(imagePath(*d)) << "</code>, sphere "
        << escapeHtml(sphereNumberText(d->get("sphere").value_or(""))) << ": " << escapeHtml(d->get("flag").value_or(""))
        << ", confidence " << confidenceText(*d) << (reason.empty() ? "" : " \u2014 ")
        << escapeHtml(reason) << "</li>";
    }
    s << "</ul>";
  }
  if (!highlights.empty()) {
    s << "<details><summary>Every highlight</summary><p>Confidence, from 0 to 1: how clearly the "
         "highlight is one small, compact peak rising above the same place in the other photographs "
         "(the lowest of its scores; docs/carrier.md); 0 for one refused. A highlight given by hand "
         "has none: it says <em>by hand</em>.</p><table><tr><th>image</th><th>sphere</th>"
         "<th>x, y (px)</th><th>flag</th><th>confidence</th><th>reason</th></tr>";
    for (const carrier::DataItem* d : highlights)
      s << "<tr><td><code>" << escapeHtml(imagePath(*d)) << "</code></td><td class=\"num\">"
        << escapeHtml(sphereNumberText(d->get("sphere").value_or(""))) << "</td><td class=\"num\">" << numberOr(*d, "x", 2)
        << ", " << numberOr(*d, "y", 2) << "</td><td>" << escapeHtml(d->get("flag").value_or(""))
        << "</td><td class=\"num\">" << confidenceText(*d) << "</td><td>"
        << escapeHtml(d->get("reason").value_or("")) << "</td></tr>";
    s << "</table></details>";
  }
  s << "<div class=\"gallery large\">";  // the overviews' labels need the pictures near full size
  bool any = false;
  for (const auto& [kind, file] : outputsByKind(c)) {
    if (kind == "sphere-overlay") {
      s << figure(pictures, *file, "Sphere detection overlay", &report.picturesEmbedded);
      any = true;
    } else if (kind == "highlight-overview") {
      s << figure(pictures, *file, "Highlight overview", &report.picturesEmbedded);
      any = true;
    }
  }
  s << "</div>";
  if (!any) s << "<p class=\"note\">No overlay or highlight overview was written.</p>";
  s << "</section>";
  return s.str();
}

// Beside the normal map: how many of its pixels took the Lambertian normal (DerivedMaps'
// normalFallbackPixels), out of the map's pixels; empty when either is unknown.
std::string normalFallbackNote(const carrier::Carrier& c, const Pictures& pictures, const carrier::FileRecord& normals) {
  const carrier::Result* r = c.findResult(normals.createdBy);
  const Pictures::Picture picture = pictures.get(normals.path);
  if (!r || !picture.embedded) return "";
  for (const carrier::DataItem* v : r->itemsOf("value")) {
    if (v->get("name") != "normalFallbackPixels") continue;
    try {
      return "<p>" + explainNormalFallback(std::llround(v->number("value")),
                                           static_cast<long long>(picture.embedded->originalWidth) *
                                               picture.embedded->originalHeight) + "</p>";
    } catch (const Error&) {
      return "";
    }
  }
  return "";
}

std::string resultsSection(const carrier::Carrier& c, const Pictures& pictures,
                           Report& report) {
  std::ostringstream s;
  s << "<section id=\"results\"><h2>Results</h2>";
  // Fit quality per model.
  std::ostringstream fits;
  for (const carrier::Step& step : c.process) {
    const carrier::Result* r = c.findResult(step.id);
    if (!r) continue;
    std::string rmse, psnr, output;
    for (const carrier::DataItem* v : r->itemsOf("value")) {
      if (v->get("name") == "rmse") rmse = v->get("value").value_or("");
      if (v->get("name") == "psnr") psnr = v->get("value").value_or("");
    }
    if (rmse.empty()) continue;
    for (const carrier::DataItem* o : r->itemsOf("output"))
      if (const carrier::FileRecord* f = c.findFile(o->get("file").value_or(""))) output = f->path;
    auto shown = [](const std::string& t) {
      try {
        return displayNumber(std::stod(t), 2);
      } catch (const std::exception&) {
        return std::string("-");
      }
    };
    std::string meaning;
    try {
      meaning = explainRmse(std::stod(rmse)) + " " + explainPsnr(std::stod(psnr));
    } catch (const std::exception&) {
      // a figure that is not a number is shown as "-", with nothing to explain
    }
    fits << "<tr><td>" << escapeHtml(stepTitle(step)) << "</td><td><code>" << escapeHtml(output) << "</code></td><td class=\"num\">" << shown(rmse)
         << "</td><td class=\"num\">" << shown(psnr) << "</td><td>" << meaning << "</td></tr>";
  }
  if (!fits.str().empty())
    s << "<table><tr><th>fit</th><th>file</th><th>RMSE (8-bit levels)</th>"
         "<th>PSNR (dB)</th><th>what it means</th></tr>" << fits.str() << "</table>";
  s << learnedFitsTable(c);
  s << heldOutTable(c);

  s << "<div class=\"gallery\">";
  for (const auto& [kind, file] : outputsByKind(c)) {
    if (kind == "normals") {
      s << figure(pictures, *file, "Normal map", &report.picturesEmbedded);
      s << normalFallbackNote(c, pictures, *file);
    }
    else if (kind == "albedo") s << figure(pictures, *file, "Albedo", &report.picturesEmbedded);
    else if (kind == "preview")
      s << figure(pictures, *file, previewCaption(file->path), &report.picturesEmbedded);
  }
  s << "</div></section>";
  return s.str();
}

// The files the detection and results sections show as pictures, in carrier order.
std::vector<std::string> shownPictures(const carrier::Carrier& c) {
  std::vector<std::string> out;
  for (const auto& [kind, file] : outputsByKind(c))
    if (kind == "sphere-overlay" || kind == "highlight-overview" || kind == "normals" || kind == "albedo" ||
        kind == "preview")
      out.push_back(file->path);
  return out;
}

// The share of the report's work done once the pictures are made: decoding, downscaling and
// re-encoding them is most of it, so the pictures are counted (the interactive models as one
// more).
double shareAfterPictures(const std::vector<std::string>& pictures) {
  return double(pictures.size()) / double(pictures.size() + 1);
}

}  // namespace

std::vector<std::pair<std::string, const carrier::FileRecord*>> outputsByKind(const carrier::Carrier& c) {
  std::vector<std::pair<std::string, const carrier::FileRecord*>> out;
  for (const carrier::Result& r : c.data)
    for (const carrier::DataItem* o : r.itemsOf("output"))
      if (const carrier::FileRecord* f = c.findFile(o->get("file").value_or("")))
        out.emplace_back(o->get("kind").value_or(""), f);
  return out;
}

Report buildReport(const carrier::Carrier& c, const ReportSource& source, const ReportOptions& options) {
  const auto progress = [&options](double f) {
    if (options.progress) options.progress(kProgressLabel, f);
  };
  progress(0);
  Report report;
  std::string fitLabel;
  const std::vector<LightPoint> lightPoints = collectLights(c, &fitLabel);
  const Coverage coverage = analyseCoverage(lightPoints);
  report.lightsPlotted = static_cast<int>(lightPoints.size());
  report.coverageGaps = coverage.sentences();
  const std::string lights = lightsSection(c, lightPoints, coverage, fitLabel);
  progress(0.05);
  Pictures pictures(source, options.maxImageSide, options.displayed);
  const std::vector<std::string> shown = shownPictures(c);
  // The models for the interactive view on a thread of their own while the pictures are made
  // on the others: neither depends on the other, so the page is the same at any thread count.
  std::vector<RelightModel> models;
  if (effectiveThreads(options.threads) > 1) {
    std::future<std::vector<RelightModel>> modelsMade =
        std::async(std::launch::async, [&] { return relightModels(c, source, options); });
    pictures.prepare(shown, options.threads);
    models = modelsMade.get();
  } else {
    pictures.prepare(shown, options.threads);
    models = relightModels(c, source, options);
  }
  progress(0.05 + 0.9 * shareAfterPictures(shown));
  const std::string detection = detectionSection(c, pictures, report);
  const std::string colour = colourSection(c);
  const std::string results = resultsSection(c, pictures, report);
  const RelightSection relight = relightSection(c, models, lightPoints, report);
  const std::string priorWork = auditSection(c, source, &report.picturesEmbedded);
  progress(0.95);
  const std::string generated = options.generatedAt.empty() ? carrier::timestampNow() : options.generatedAt;

  std::ostringstream head, tail;
  head << "<!DOCTYPE html>\n<html lang=\"en\"><head><meta charset=\"utf-8\">"
          "<meta http-equiv=\"Content-Security-Policy\" content=\"default-src 'none'; img-src data:; "
          "style-src 'unsafe-inline'; script-src 'unsafe-inline'\">"
          "<meta name=\"viewport\" content=\"width=device-width, initial-scale=1\">"
          "<meta name=\"generator\" content=\"Surrogate " << escapeHtml(surrogateVersion()) << "\">"
       << "<title>" << escapeHtml(c.header.title) << " \u2014 Surrogate report</title><style>" << kReportCss
       << "</style></head>\n<body data-lights-expected=\"" << report.lightsPlotted << "\">\n<header><h1>"
       << escapeHtml(c.header.title) << "</h1><p class=\"note\">From the " << escapeHtml(source.describe())
       << "; report made " << escapeHtml(generated) << " by Surrogate " << escapeHtml(surrogateVersion())
       << ".</p></header>\n<main>" << auditSummarySection(c)
       << summarySection(c, lightPoints, coverage, options.verification)
       // Side by side when the window has room for both (a small model and its light plot).
       << "<div class=\"first-row\">";
  tail << provenanceSection(c) << "<div class=\"columns\">" << cameraSection(c)
       << verificationSection(options.verification) << filesSection(c) << "</div></main>\n<footer class=\"note\">Carrier created "
       << escapeHtml(c.header.created) << ", last changed " << escapeHtml(c.header.modified)
       << ". This page is a view of the carrier (assembly-files/carrier.xml), which is the record; the "
          "report itself is not part of the recorded provenance.</footer>\n<script>" << kPageErrorsJs << kRelightModelJs
       << kRelightViewJs << kReportJs << "</script>\n</body></html>\n";
  // The sections with pictures and models are megabytes: appended once each to a page of
  // the right size, not streamed.
  const std::string first = head.str(), last = tail.str();
  reserveResident(report.html, first.size() + relight.size() + lights.size() + detection.size() +
                                   colour.size() + results.size() + priorWork.size() + last.size() + 8);
  report.html.append(first);
  relight.appendTo(report.html);
  report.html.append(lights).append("</div>").append(detection).append(colour).append(results).append(priorWork).append(last);
  progress(1);
  return report;
}

Report writeCaptureReport(const std::filesystem::path& capture, const ReportOptions& options) {
  const std::unique_ptr<ReportSource> source = openReportSource(capture);
  Report r = buildReport(source->carrier(), *source, options);
  std::filesystem::create_directories(capture / capture::kFinishedDir);
  // The half-written page waits in the capture's work folder, not in finished-files/: a command
  // killed while it writes leaves nothing there that the carrier does not describe (the next
  // command removes the leftover, run/run_commit.h).
  std::filesystem::create_directories(capture / capture::kWorkDir);
  AtomicFile page(capture / capture::kReportPath, capture / capture::kWorkDir);
  writeTemporary(page, r.html);
  // Fault injection for the test of this guarantee (tests/e2e/test_workflow_e2e.cpp): with
  // SURROGATE_FAULT_INJECTION=report the process dies with the page written but not in place.
  if (const char* fault = std::getenv("SURROGATE_FAULT_INJECTION"); fault && std::string(fault) == "report")
    std::_Exit(137);
  page.commit();
  return r;
}

}  // namespace surrogate::report
