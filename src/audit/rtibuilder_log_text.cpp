// RTIBuilder's log as surrogate info shows it (text and JSON), and its comparison with the
// capture (rtibuilder_log.h). Every string here was escaped when the log was read.
#include <algorithm>
#include <map>
#include <set>
#include <sstream>

#include "audit/rtibuilder_log.h"
#include "core/json.h"
#include "core/text.h"

namespace surrogate::audit {

namespace {

// How many file names a text line lists before "and N more".
constexpr std::size_t kNamesShown = 8;

std::string listed(const std::vector<std::string>& names) { return listedWithMore(names, kNamesShown); }

std::string items(const std::vector<LogItem>& list) {
  std::string out;
  for (const LogItem& i : list) out += (out.empty() ? "" : ", ") + i.name + " " + i.value;
  return out;
}

// Numbers of the log to 0.1 pixel for display (--json has them whole).
std::string pixels(double v) {
  std::string s = fixedDecimals(v, 1);
  if (s.size() > 2 && s.compare(s.size() - 2, 2, ".0") == 0) s.resize(s.size() - 2);
  return s;
}

// A name as the comparison matches it: the file name without its extension, in lower case.
std::string matchKey(const std::string& path) {
  const auto slash = path.find_last_of("\\/");
  std::string name = slash == std::string::npos ? path : path.substr(slash + 1);
  const auto dot = name.rfind('.');
  if (dot != std::string::npos && dot > 0) name.resize(dot);
  return lowerCase(name);
}

void itemsJson(JsonWriter& j, const std::vector<LogItem>& list) {
  j.beginArray();
  for (const LogItem& i : list) j.beginObject().key("name").value(i.name).key("value").value(i.value).endObject();
  j.endArray();
}

void pointsJson(JsonWriter& j, const std::vector<LogPoint>& points, bool withZ) {
  j.beginArray();
  for (const LogPoint& p : points) {
    j.beginObject().key("image").value(p.image).key("x").value(p.x).key("y").value(p.y);
    if (withZ) j.key("z").value(p.z);
    j.endObject();
  }
  j.endArray();
}

void stringsJson(JsonWriter& j, const std::vector<std::string>& list) {
  j.beginArray();
  for (const std::string& s : list) j.value(s);
  j.endArray();
}

}  // namespace

std::string RtiBuilderLog::toText() const {
  std::ostringstream o;
  o << path << ": RTIBuilder log (" << software << (version.empty() ? "" : " " + version) << ")\n";
  if (!projectName.empty() || !author.empty()) {
    o << "  project:     " << (projectName.empty() ? "(no name)" : projectName);
    if (!author.empty()) o << ", by " << author;
    if (!host.empty()) o << " on " << host;
    if (!operatingSystem.empty()) o << " (" << operatingSystem << ")";
    o << "\n";
  }
  if (!created.empty()) o << "  created:     " << created << (modified.empty() || modified == created ? "" : ", last modified " + modified) << "\n";
  o << "  images:      " << images.size() << " listed, " << usedImages.size() << " used, " << excludedImages.size() << " excluded";
  if (imageWidth > 0 && imageHeight > 0) o << ", " << imageWidth << "x" << imageHeight;
  o << "\n";
  if (!excludedImages.empty()) o << "  excluded:    " << listed(excludedImages) << "\n";
  for (std::size_t i = 0; i < spheres.size(); ++i) {
    const LogSphere& s = spheres[i];
    o << "  sphere " << i + 1 << ":    centre " << pixels(s.x) << ", " << pixels(s.y) << ", radius " << pixels(s.radius);
    if (s.detectionImages > 0 || !s.detection.empty())
      o << "; found on " << s.detectionImages << " images (" << items(s.detection) << ")";
    o << "\n              " << s.highlights.size() << " highlights";
    if (!s.highlightDetection.empty()) o << " (" << items(s.highlightDetection) << ")";
    o << ", " << s.lightDirections.size() << " light directions\n";
  }
  if (!highlightMethod.empty()) o << "  highlights:  detection step " << highlightMethod << "\n";
  if (fitter) {
    o << "  fitter:      " << fitter->name;
    if (fitter->order > 0) o << ", HSH order " << fitter->order << " (" << fitter->basis << ")";
    if (fitter->threads > 0) o << ", " << fitter->threads << " threads";
    if (!fitter->options.empty()) o << ", options " << listed(fitter->options);
    o << "\n";
    if (!fitter->lightFile.empty()) o << "  light file:  " << fitter->lightFile << "\n";
    if (!fitter->output.empty()) o << "  model:       " << fitter->output << "\n";
    o << "  fit:         " << (fitter->result.empty() ? "the log does not say how the fit ended" : fitter->result) << "\n";
  }
  if (!outputs.empty()) {
    std::vector<std::string> names;
    for (const LogFile& f : outputs) names.push_back(f.path);
    o << "  files:       " << outputs.size() << " written: " << listed(names) << "\n";
  }
  std::map<std::string, int> levels;
  for (const LogEvent& e : events) ++levels[lowerCase(e.level)];
  o << "  messages:    " << events.size();
  std::string byLevel;
  for (const auto& [level, n] : levels) byLevel += (byLevel.empty() ? "" : ", ") + std::to_string(n) + " " + (level.empty() ? "without level" : level);
  if (!byLevel.empty()) o << " (" << byLevel << ")";
  o << "\n  other:       " << other.size() << " items the reader does not classify (--json lists them)";
  return o.str();
}

std::string RtiBuilderLog::toJson() const {
  JsonWriter j;
  j.beginObject().key("kind").value("rtibuilder-log").key("file").value(path).key("software").value(software)
      .key("version").value(version).key("versionFrom").value(versionFrom).key("project").value(projectName)
      .key("author").value(author).key("host").value(host).key("operatingSystem").value(operatingSystem)
      .key("created").value(created).key("modified").value(modified).key("imageWidth").value(imageWidth)
      .key("imageHeight").value(imageHeight);
  j.key("images").beginArray();
  for (const LogFile& f : images) j.value(f.path);
  j.endArray().key("usedImages");
  stringsJson(j, usedImages);
  j.key("excludedImages");
  stringsJson(j, excludedImages);
  j.key("reportedImagesUsed").value(reportedImagesUsed).key("highlightMethod").value(highlightMethod);
  j.key("spheres").beginArray();
  for (const LogSphere& s : spheres) {
    j.beginObject().key("id").value(s.id).key("order").value(s.order).key("x").value(s.x).key("y").value(s.y)
        .key("radius").value(s.radius).key("detectionImages").value(s.detectionImages).key("detection");
    itemsJson(j, s.detection);
    j.key("highlightDetection");
    itemsJson(j, s.highlightDetection);
    j.key("highlights");
    pointsJson(j, s.highlights, false);
    j.key("lightDirections");
    pointsJson(j, s.lightDirections, true);
    j.endObject();
  }
  j.endArray().key("fitter");
  if (fitter) {
    j.beginObject().key("name").value(fitter->name).key("kind").value(fitter->kind).key("basis").value(fitter->basis)
        .key("order").value(fitter->order).key("threads").value(fitter->threads).key("commandLine").value(fitter->commandLine)
        .key("lightFile").value(fitter->lightFile).key("output").value(fitter->output).key("options");
    stringsJson(j, fitter->options);
    j.key("result").value(fitter->result).key("succeeded").value(fitter->succeeded).endObject();
  } else {
    j.null();
  }
  j.key("outputs").beginArray();
  for (const LogFile& f : outputs) j.beginObject().key("path").value(f.path).key("use").value(f.use).endObject();
  j.endArray().key("events").beginArray();
  for (const LogEvent& e : events)
    j.beginObject().key("level").value(e.level).key("text").value(e.text).key("started").value(e.started)
        .key("finished").value(e.finished).endObject();
  j.endArray().key("other");
  itemsJson(j, other);
  j.endObject();
  return j.str();
}

std::vector<std::string> logDiscrepancies(const RtiBuilderLog& log, const CaptureFacts& capture) {
  std::vector<std::string> out;
  std::set<std::string> photographs;
  for (const std::string& p : capture.photographs) photographs.insert(matchKey(p));
  std::set<std::string> listedKeys, usedKeys;
  for (const LogFile& f : log.images) listedKeys.insert(matchKey(f.path));
  for (const std::string& u : log.usedImages) usedKeys.insert(matchKey(u));

  if (!capture.photographs.empty()) {
    std::vector<std::string> strangers, unlisted;
    for (const std::string& u : log.usedImages)
      if (!photographs.count(matchKey(u))) strangers.push_back(u);
    for (const std::string& p : capture.photographs)
      if (!listedKeys.count(matchKey(p)) && !usedKeys.count(matchKey(p))) unlisted.push_back(escapedText(p));
    if (!strangers.empty())
      out.push_back("the log used " + std::to_string(strangers.size()) + " image(s) that are not among the capture's photographs: " + listed(strangers));
    if (!unlisted.empty())
      out.push_back(std::to_string(unlisted.size()) + " photograph(s) of the capture are not in the log: " + listed(unlisted));
  }
  if (!log.excludedImages.empty())
    out.push_back("the log lists " + std::to_string(log.excludedImages.size()) + " image(s) it did not use: " + listed(log.excludedImages));
  if (capture.photographCount > 0 && log.usedImages.size() != capture.photographCount)
    out.push_back("the log used " + std::to_string(log.usedImages.size()) + " images; the capture has " +
                  std::to_string(capture.photographCount) + " photographs");
  // RTIBuilder counts an image once per sphere it sought highlights on.
  const std::size_t perSphere = std::max<std::size_t>(1, log.spheres.size());
  if (log.reportedImagesUsed >= 0 && static_cast<std::size_t>(log.reportedImagesUsed) != log.usedImages.size() &&
      static_cast<std::size_t>(log.reportedImagesUsed) != log.usedImages.size() * perSphere)
    out.push_back("the log's messages say " + std::to_string(log.reportedImagesUsed) + " images were used, but it lists " +
                  std::to_string(log.usedImages.size()));
  if (capture.width > 0 && log.imageWidth > 0 && (capture.width != log.imageWidth || capture.height != log.imageHeight))
    out.push_back("the log's images are " + std::to_string(log.imageWidth) + "x" + std::to_string(log.imageHeight) +
                  "; the photographs are " + std::to_string(capture.width) + "x" + std::to_string(capture.height));
  if (capture.spheres > 0 && !log.spheres.empty() && static_cast<std::size_t>(capture.spheres) != log.spheres.size())
    out.push_back("the log found " + std::to_string(log.spheres.size()) + " sphere(s); Surrogate found " + std::to_string(capture.spheres));
  for (std::size_t i = 0; i < log.spheres.size(); ++i) {
    const LogSphere& s = log.spheres[i];
    if (!s.lightDirections.empty() && s.lightDirections.size() != log.usedImages.size())
      out.push_back("the log has light directions for " + std::to_string(s.lightDirections.size()) + " of its " +
                    std::to_string(log.usedImages.size()) + " images on sphere " + std::to_string(i + 1));
  }
  if (log.fitter && !capture.basis.empty() && !log.fitter->basis.empty() && log.fitter->basis != capture.basis)
    out.push_back("the log's fit is " + log.fitter->basis + "; the prior model audited is " + escapedText(capture.basis));
  if (log.fitter && !log.fitter->succeeded)
    out.push_back("the log does not say that its fit (" + log.fitter->name + ") succeeded");
  return out;
}

AuditReport::PriorLog auditedLog(const RtiBuilderLog& log, const std::string& relativePath,
                                 const CaptureFacts& capture) {
  AuditReport::PriorLog out;
  out.file = std::filesystem::u8path(relativePath);
  std::istringstream lines(log.toText());
  std::string line;
  std::getline(lines, line);  // "<path>: RTIBuilder log (...)": the file is named apart
  out.records.push_back(log.software + (log.version.empty() ? "" : " " + log.version));
  while (std::getline(lines, line)) {
    const auto first = line.find_first_not_of(' ');
    if (first == std::string::npos) continue;
    std::string fact = line.substr(first);
    // "images:      36 listed" -> "images: 36 listed"
    const auto colon = fact.find(':');
    if (colon != std::string::npos) {
      const auto value = fact.find_first_not_of(' ', colon + 1);
      if (value != std::string::npos) fact = fact.substr(0, colon + 1) + " " + fact.substr(value);
    } else if (!out.records.empty() && out.records.size() > 1) {
      out.records.back() += "; " + fact;  // a continuation line
      continue;
    }
    out.records.push_back(fact);
  }
  out.discrepancies = logDiscrepancies(log, capture);
  return out;
}

}  // namespace surrogate::audit
