// Reading RTIBuilder's log (rtibuilder_log.h): the XMLCarrier document read whole through
// carrier/xml.h, then each section classified; what is not classified goes to `other`.
#include "audit/rtibuilder_log.h"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdlib>
#include <fstream>
#include <map>
#include <regex>
#include <set>

#include "carrier/xml.h"
#include "core/atomic_file.h"
#include "core/error.h"
#include "core/text.h"

namespace surrogate::audit {

namespace fs = std::filesystem;

namespace {

constexpr const char* kStep = "RTIBuilder log";
// What a log's root element is, for the message refusing another file.
constexpr const char* kWhatALogIs =
    "an RTIBuilder log: the XML document RTIBuilder keeps in a project's assembly-files/, whose "
    "root element is <XMLCarrier> in the namespace http://alba.di.uminho.pt/XMLCarrier";
// Elements flattened into `other` at most: a log with more unclassified data is still read.
constexpr std::size_t kMaxOtherItems = 2000;

// Text from the file as the struct keeps it: escaped, and cut at kMaxLogValueBytes on a UTF-8
// boundary (escaped text is valid UTF-8).
std::string clean(const std::string& raw) {
  std::string s = escapedText(raw);
  if (s.size() <= kMaxLogValueBytes) return s;
  std::size_t n = kMaxLogValueBytes;
  while (n > 0 && (static_cast<unsigned char>(s[n]) & 0xC0) == 0x80) --n;
  return s.substr(0, n) + "...";
}

std::string trimmed(const std::string& s) {
  const auto b = s.find_first_not_of(" \t\r\n");
  if (b == std::string::npos) return "";
  return s.substr(b, s.find_last_not_of(" \t\r\n") - b + 1);
}

double number(const std::string& s) {
  char* end = nullptr;
  const double v = std::strtod(s.c_str(), &end);
  return end != s.c_str() && std::isfinite(v) ? v : 0.0;
}

int integer(const std::string& s) {
  const double v = number(s);
  return v >= 0 && v < 1e9 ? static_cast<int>(v) : 0;
}

// The file name of a path the log writes (Windows or POSIX separators).
std::string fileName(const std::string& path) {
  const auto slash = path.find_last_of("\\/");
  return slash == std::string::npos ? path : path.substr(slash + 1);
}

// Attributes of an area that place it rather than parameterise the step.
bool isPlacement(const std::string& name) {
  static const std::set<std::string> k = {"BEGIN", "END", "COORDS", "SHAPE", "UUID", "fileGrpID",
                                          "projectName", "projectPath", "x", "y", "r"};
  return k.count(name) > 0;
}

struct Reader {
  RtiBuilderLog& log;
  std::map<std::string, std::string> imageNames;             // file id -> file name
  std::map<std::string, std::vector<std::string>> groups;    // group id -> file ids
  std::map<std::string, std::string> processInputs;          // process type -> input data id
  std::map<std::string, const xml::Element*> data;           // data id -> element
  std::set<std::string> classifiedData;
  std::map<std::string, std::vector<LogPoint>> dataHighlights;  // sphere id -> dataSec's highlights

  void other(const std::string& name, const std::string& value) {
    if (log.other.size() < kMaxOtherItems) log.other.push_back({clean(name), clean(value)});
  }
  // Every attribute and text of `e` and its descendants, by path.
  void flatten(const xml::Element& e, const std::string& prefix) {
    const std::string path = prefix + e.name;
    for (const auto& [n, v] : e.attributes) other(path + "@" + n, v);
    if (!trimmed(e.text).empty() || (e.children.empty() && e.attributes.empty())) other(path, trimmed(e.text));
    for (const xml::Element& c : e.children) flatten(c, path + "/");
  }
  std::string imageName(const std::string& id) const {
    const auto it = imageNames.find(id);
    return it == imageNames.end() ? clean(id) : it->second;
  }
  LogSphere& sphere(const std::string& id) {
    for (LogSphere& s : log.spheres)
      if (s.id == clean(id)) return s;
    log.spheres.push_back({});
    log.spheres.back().id = clean(id);
    return log.spheres.back();
  }

  void header(const xml::Element& h) {
    if (!h.attribute("UUID").empty()) other("Header@UUID", h.attribute("UUID"));
    for (const xml::Element& c : h.children) {
      const std::string t = clean(trimmed(c.text));
      if (c.name == "ProjectName") log.projectName = t;
      else if (c.name == "Author") log.author = t;
      else if (c.name == "Host") log.host = t;
      else if (c.name == "CreationDate") log.created = t;
      else if (c.name == "LastModificationDate") log.modified = t;
      else if (c.name == "AdditionalInfo") additionalInfo(c);
      else flatten(c, "Header/");
    }
  }
  void additionalInfo(const xml::Element& a) {
    for (const xml::Element& c : a.children) {
      if (c.name == "Info") {
        for (const auto& [n, v] : c.attributes) {
          if (n == "OperatingSystem") log.operatingSystem = clean(v);
          else other("Info@" + n, v);
        }
      } else if (c.name == "Info2") {
        const std::string n = c.attribute("NAME"), v = c.attribute("VALUE");
        if (n == "Image width") log.imageWidth = integer(v);
        else if (n == "Image height") log.imageHeight = integer(v);
        else other(n, v);
      } else {
        flatten(c, "Header/AdditionalInfo/");
      }
    }
  }

  void fileSec(const xml::Element& f) {
    for (const xml::Element& g : f.children) {
      if (g.name != "fileGrp") { flatten(g, "fileSec/"); continue; }
      const std::string use = g.attribute("USE");
      std::vector<std::string>& members = groups[g.attribute("ID")];
      for (const xml::Element& c : g.children) {
        if (c.name == "fptr") {
          members.push_back(trimmed(c.text));
        } else if (c.name == "file") {
          const xml::Element* loc = c.child("FLocat");
          const std::string href = loc ? loc->attribute("xlink:href") : "";
          members.push_back(c.attribute("ID"));
          if (use == "Original image files") {
            imageNames[c.attribute("ID")] = clean(fileName(href));
            log.images.push_back({clean(href), clean(use)});
          } else {
            log.outputs.push_back({clean(href), clean(use)});
          }
        } else {
          flatten(c, "fileSec/fileGrp/");
        }
      }
    }
  }

  void processes(const xml::Element& p) {
    for (const xml::Element& c : p.children) {
      if (c.name != "process") { flatten(c, "Processes/"); continue; }
      const std::string type = c.attribute("TYPE");
      if (type == "PIPELINE") continue;  // RTIBuilder's placeholders for its pipeline, no data
      if (const xml::Element* in = c.child("Input"))
        for (const xml::Element& r : in->children)
          if (r.name == "ref") processInputs[type] = trimmed(r.text);
      if (type == "HLTDETECTION") log.highlightMethod = clean(type);
      if (type != "HLTDETECTION" && type != "BALLDETECTION") flatten(c, "Processes/");
    }
  }

  // The search areas of the sphere detection's or highlight detection's input data.
  void detectionInput(const std::string& type, bool highlights) {
    const auto id = processInputs.find(type);
    if (id == processInputs.end() || !data.count(id->second)) return;
    classifiedData.insert(id->second);
    for (const xml::Element& area : data[id->second]->children) {
      if (area.name != "area") continue;
      LogSphere& s = sphere(area.attribute("UUID"));
      std::vector<LogItem>& items = highlights ? s.highlightDetection : s.detection;
      items.push_back({"search area", clean(area.attribute("BEGIN") + " to " + area.attribute("END"))});
      for (const auto& [n, v] : area.attributes)
        if (!isPlacement(n)) items.push_back({clean(n), clean(v)});
      const auto g = groups.find(area.attribute("fileGrpID"));
      const int count = g == groups.end() ? 0 : static_cast<int>(g->second.size());
      if (highlights) {
        if (g != groups.end())
          for (const std::string& fid : g->second) log.usedImages.push_back(imageName(fid));
      } else {
        s.detectionImages = count;
      }
    }
  }

  // The highlights the detection's output areas refer to (Ref_HighLights: x1, y1, img1, ...):
  // kept for a sphere whose computedData lists none.
  void highlightOutputs() {
    for (const auto& [id, d] : data) {
      for (const xml::Element& area : d->children) {
        const std::string ref = area.attribute("Ref_HighLights");
        if (area.name != "area" || ref.empty() || !data.count(ref)) continue;
        std::map<std::string, std::string> params;
        for (const xml::Element& p : data[ref]->children)
          if (p.name == "param") params[p.attribute("NAME")] = trimmed(p.text);
        std::vector<LogPoint>& points = dataHighlights[clean(area.attribute("UUID"))];
        for (int i = 1; params.count("img" + std::to_string(i)); ++i) {
          const std::string n = std::to_string(i);
          points.push_back({imageName(params["img" + n]), number(params["x" + n]), number(params["y" + n]), 0});
        }
      }
    }
  }

  void computedData(const xml::Element& c) {
    for (const xml::Element& e : c.children) {
      if (e.name == "Images") continue;  // names the original images' group, read already
      if (e.name == "Spheres") {
        for (const xml::Element& s : e.children) {
          if (s.name != "sphere") { flatten(s, "computedData/Spheres/"); continue; }
          LogSphere& out = sphere(s.attribute("ID"));
          const std::string order = s.attribute("Order");
          if (!order.empty()) out.order = integer(order);
          out.x = number(s.attribute("x"));
          out.y = number(s.attribute("y"));
          out.radius = number(s.attribute("r"));
        }
      } else if (e.name == "HighLights" || e.name == "LightDirections") {
        LogSphere& out = sphere(e.attribute("SphereID"));
        for (const xml::Element& p : e.children) {
          const LogPoint point{imageName(p.attribute("ImageID")), number(p.attribute("x")),
                               number(p.attribute("y")), number(p.attribute("z"))};
          (e.name == "HighLights" ? out.highlights : out.lightDirections).push_back(point);
        }
      } else {
        flatten(e, "computedData/");
      }
    }
  }

  // "Command line to execute : EXE LP ARGS... OUT": the executable ends at ".exe " (paths may
  // hold spaces), the light file at ".lp ", the numbers after it are options, the rest is the
  // model written.
  void fitterCommand(const std::string& raw) {
    LogFitter f;
    f.commandLine = clean(raw);
    std::string lower = lowerCase(raw);
    auto exeEnd = lower.find(".exe ");
    if (exeEnd == std::string::npos) exeEnd = lower.find(' ');
    else exeEnd += 4;
    const std::string exe = raw.substr(0, exeEnd);
    std::string name = fileName(exe);
    if (lowerCase(name).size() > 4 && lowerCase(name).substr(name.size() - 4) == ".exe") name.resize(name.size() - 4);
    f.name = clean(name);
    const std::string lname = lowerCase(name);
    f.kind = lname.find("hsh") != std::string::npos ? "HSH" : lname.find("ptm") != std::string::npos ? "PTM" : "";
    std::string rest = exeEnd == std::string::npos ? "" : trimmed(raw.substr(exeEnd));
    const auto lpEnd = lowerCase(rest).find(".lp ");
    if (lpEnd != std::string::npos) {
      f.lightFile = clean(rest.substr(0, lpEnd + 3));
      rest = trimmed(rest.substr(lpEnd + 3));
    }
    std::vector<std::string> numbers;
    while (!rest.empty() && std::isdigit(static_cast<unsigned char>(rest[0]))) {
      const auto space = rest.find(' ');
      if (space == std::string::npos) break;
      numbers.push_back(rest.substr(0, space));
      rest = trimmed(rest.substr(space));
    }
    f.output = clean(rest);
    if (f.kind == "HSH" && !f.lightFile.empty() && numbers.size() == 2) {
      f.order = integer(numbers[0]);
      f.threads = integer(numbers[1]);
      if (f.order >= 2 && f.order <= 4) f.basis = "hsh" + std::to_string(f.order);
    } else {
      for (const std::string& n : numbers) f.options.push_back(clean(n));
    }
    if (!f.lightFile.empty()) log.outputs.push_back({f.lightFile, "fitter input"});
    if (!f.output.empty()) log.outputs.push_back({f.output, "fitter output"});
    log.fitter = f;
  }

  void events(const xml::Element& l) {
    static const std::regex kVersion(R"(rtibuilder[_ -]?v?(\d+)[_.](\d+)[_.](\d+))", std::regex::icase);
    for (const xml::Element& e : l.children) {
      if (e.name != "event") { flatten(e, "Log/"); continue; }
      const std::string text = trimmed(e.text);
      log.events.push_back({clean(e.attribute("LEVEL")), clean(text), clean(e.attribute("DATES")), clean(e.attribute("DATEF"))});
      std::smatch m;
      if (log.version.empty() && std::regex_search(text, m, kVersion)) {
        log.version = m[1].str() + "." + m[2].str() + "." + m[3].str();
        log.versionFrom = "the install folder its messages name (" + clean(m[0].str()) + ")";
      }
      const std::string kCommand = "Command line to execute :";
      if (text.compare(0, kCommand.size(), kCommand) == 0) fitterCommand(trimmed(text.substr(kCommand.size())));
      const std::string kUsed = "Number of images used :";
      if (text.compare(0, kUsed.size(), kUsed) == 0) log.reportedImagesUsed = integer(trimmed(text.substr(kUsed.size())));
      if (log.fitter && text.find("was generated successfully") != std::string::npos) {
        log.fitter->result = clean(text);
        log.fitter->succeeded = true;
      } else if (log.fitter && lowerCase(text).find("fitter return") != std::string::npos) {
        log.fitter->result = clean(text);
      }
    }
  }
};

}  // namespace

bool looksLikeRtiBuilderLog(const fs::path& file) {
  std::ifstream in(file, std::ios::binary);
  std::string head(4096, '\0');
  in.read(head.data(), static_cast<std::streamsize>(head.size()));
  head.resize(static_cast<std::size_t>(in.gcount()));
  std::size_t i = 0;
  while ((i = head.find('<', i)) != std::string::npos) {
    if (i + 1 < head.size() && (head[i + 1] == '?' || head[i + 1] == '!')) {
      ++i;
      continue;
    }
    std::size_t end = i + 1;
    while (end < head.size() && !std::isspace(static_cast<unsigned char>(head[end])) && head[end] != '>' && head[end] != '/') ++end;
    const std::string name = head.substr(i + 1, end - i - 1);
    const auto colon = name.find(':');
    return (colon == std::string::npos ? name : name.substr(colon + 1)) == "XMLCarrier";
  }
  return false;
}

RtiBuilderLog readRtiBuilderLog(const fs::path& file) {
  const std::string source = file.string();
  std::error_code ec;
  const std::uintmax_t bytes = fs::file_size(file, ec);
  if (ec) throwInputError(source, kStep, "cannot be read (" + ec.message() + ")");
  if (bytes > kMaxLogBytes)
    throwInputError(source, kStep, "is " + std::to_string(bytes) + " bytes, larger than any RTIBuilder log (Surrogate reads up to " +
                                       std::to_string(kMaxLogBytes) + "); it is not read");
  const xml::Element root = xml::readElementTree(readFile(file, kStep), source, kMaxLogElements);
  if (root.name != "XMLCarrier" || root.namespaceUri != kRtiBuilderLogNamespace)
    throwInputError(source, kStep, "is not " + std::string(kWhatALogIs) + "; its root element is <" + clean(root.name) + ">" +
                                       (root.namespaceUri.empty() ? std::string(" in no namespace") : " in " + clean(root.namespaceUri)));
  RtiBuilderLog log;
  log.path = clean(source);
  Reader r{log, {}, {}, {}, {}, {}, {}};
  // Sections in dependency order: file ids before the steps that name them.
  for (const char* section : {"Header", "fileSec", "Processes", "dataSec", "computedData", "Log"}) {
    const xml::Element* e = root.child(section);
    if (!e) continue;
    const std::string name = section;
    if (name == "Header") r.header(*e);
    else if (name == "fileSec") r.fileSec(*e);
    else if (name == "Processes") r.processes(*e);
    else if (name == "dataSec") {
      for (const xml::Element& d : e->children)
        if (d.name == "Data") r.data[d.attribute("UUID")] = &d;
      r.detectionInput("BALLDETECTION", false);
      r.detectionInput("HLTDETECTION", true);
      r.highlightOutputs();
      for (const xml::Element& d : e->children) {
        const std::string uuid = d.attribute("UUID");
        const bool points = d.child("param") != nullptr;          // highlights, as in computedData
        const bool outputs = d.child("area") && !r.classifiedData.count(uuid);  // derived areas
        if (d.name != "Data" || (!points && !outputs)) r.flatten(d, "dataSec/");
      }
    } else if (name == "computedData") r.computedData(*e);
    else r.events(*e);
  }
  for (const xml::Element& c : root.children) {
    static const std::set<std::string> known = {"Header", "fileSec", "Processes", "dataSec", "computedData", "Log"};
    if (!known.count(c.name)) r.flatten(c, "");
  }
  for (LogSphere& s : log.spheres)
    if (s.highlights.empty() && r.dataHighlights.count(s.id)) s.highlights = r.dataHighlights[s.id];
  // Spheres in RTIBuilder's order.
  std::stable_sort(log.spheres.begin(), log.spheres.end(),
                   [](const LogSphere& a, const LogSphere& b) { return a.order < b.order; });
  // Used: the images of the highlight detection (the same set for each sphere), in the
  // original images' order; without that step, the images light directions were found for.
  std::set<std::string> used(log.usedImages.begin(), log.usedImages.end());
  if (used.empty())
    for (const LogSphere& s : log.spheres)
      for (const LogPoint& p : s.lightDirections) used.insert(p.image);
  log.usedImages.clear();
  for (const LogFile& f : log.images) {
    const std::string name = fileName(f.path);
    (used.count(name) ? log.usedImages : log.excludedImages).push_back(name);
    used.erase(name);
  }
  for (const std::string& unlisted : used) log.usedImages.push_back(unlisted);  // ids of unlisted images
  return log;
}

}  // namespace surrogate::audit
