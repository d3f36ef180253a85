// surrogate info FILE: what a package, carrier, capture folder, image, .ptm, .rti, .lp or
// RTIBuilder log holds.
#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <iostream>
#include <map>
#include <optional>
#include <sstream>
#include <system_error>

#include "archive/bag.h"
#include "archive/bag_text.h"
#include "archive/package_reader.h"
#include "audit/rtibuilder_log.h"
#include "capture/capture.h"
#include "carrier/carrier.h"
#include "cli/args.h"
#include "cli/commands.h"
#include "core/error.h"
#include "core/json.h"
#include "core/text.h"
#include "image/decode.h"
#include "image/raw_settings.h"
#include "meta/camera_text.h"
#include "meta/metadata.h"
#include "formats/summary.h"
#include "publish/web_layout.h"
#include "run/plan.h"
#include "stages/web_copy_stage.h"

namespace surrogate::cli {

namespace fs = std::filesystem;

namespace {

// Numbers in a carrier's text values ("339,57,45", or an old carrier's
// "326.00000000000006,70") to 0.1 for display; other text as it is.
std::string shownValue(const std::string& value) {
  std::string out;
  std::size_t start = 0;
  while (start <= value.size()) {
    const std::size_t comma = std::min(value.find(',', start), value.size());
    const std::string part = value.substr(start, comma - start);
    char* end = nullptr;
    const double v = std::strtod(part.c_str(), &end);
    if (part.empty() || end != part.c_str() + part.size() || !std::isfinite(v)) return value;
    std::string t = fixedDecimals(v, 1);
    if (t.size() > 2 && t.compare(t.size() - 2, 2, ".0") == 0) t.resize(t.size() - 2);
    out += (out.empty() ? "" : ",") + t;
    start = comma + 1;
  }
  return out;
}

// What an intervention does, in words: which images, which sphere.
std::string interventionWhat(const carrier::Intervention& i) {
  if (i.kind == "exclude-image") return i.target + " is left out of every step";
  if (i.kind == "manual-sphere") return "circle of sphere " + i.target + " given by hand (x,y,r " + shownValue(i.value) + ")";
  if (i.kind == "manual-highlight") {
    const auto colon = i.target.rfind(':');
    const std::string image = i.target.substr(0, colon), sphere = colon == std::string::npos ? "" : i.target.substr(colon + 1);
    return "highlight of " + image + (sphere.empty() ? "" : " on sphere " + sphere) + " given by hand (x,y " +
           shownValue(i.value) + ")";
  }
  if (i.kind == "accept-changed-original") return "the changed " + i.target + " accepted as it is now";
  return i.target + (i.value.empty() ? "" : " = " + shownValue(i.value));
}

// The processing choices a carrier records besides the human interventions: what a run without
// options repeats (run::standingDecisions), and the web copy with its recorded options.
struct Choices {
  run::RunRequest standing;
  const carrier::Step* webCopy = nullptr;  // the first WebCopy step: every model's has the same options
  std::vector<std::string> webModels;
};

Choices choicesOf(const carrier::Carrier& c) {
  Choices out;
  out.standing = run::standingDecisions(c);
  // The decoding step records every LibRaw setting; the choices are those that differ from
  // the defaults.
  const auto defaults = image::RawDecodeSettings{}.toParameters();
  auto& decode = out.standing.decodeSettings;
  decode.erase(std::remove_if(decode.begin(), decode.end(),
                              [&](const auto& kv) { return std::find(defaults.begin(), defaults.end(), kv) != defaults.end(); }),
               decode.end());
  // The web copy's options are shown with it.
  auto& params = out.standing.stageParams;
  params.erase(std::remove_if(params.begin(), params.end(),
                              [](const auto& p) { return p.component == stages::WebCopyStage::kComponent; }),
               params.end());
  for (const carrier::Step& s : c.process) {
    if (s.component != stages::WebCopyStage::kComponent) continue;
    if (!out.webCopy) out.webCopy = &s;
    out.webModels.push_back(s.param("model"));
  }
  return out;
}

std::string joined(const std::vector<std::string>& items) {
  std::string out;
  for (const std::string& i : items) out += (out.empty() ? "" : ", ") + i;
  return out;
}

std::string paramsText(const std::vector<std::pair<std::string, std::string>>& params) {
  std::string out;
  for (const auto& [name, value] : params) out += (out.empty() ? "" : ", ") + name + " " + shownValue(value);
  return out;
}

// A carrier whose steps this version cannot read (another version's, or a forged one) still
// gets described: its choices are then left out, saying why, and `verify` judges it.
std::optional<Choices> readableChoices(const carrier::Carrier& c, std::string* why) {
  try {
    return choicesOf(c);
  } catch (const Error& e) {
    if (why) *why = e.message();
    return std::nullopt;
  }
}

void choicesJson(JsonWriter& j, const carrier::Carrier& c) {
  const std::optional<Choices> readable = readableChoices(c, nullptr);
  if (!readable) {
    j.key("choices").null();
    return;
  }
  const Choices& ch = *readable;
  const run::RunRequest& r = ch.standing;
  j.key("choices").beginObject().key("source").value(r.source.empty() ? "auto" : r.source).key("bases").beginArray();
  for (const std::string& b : r.bases.value_or(std::vector<std::string>{})) j.value(b);
  j.endArray().key("decode").beginArray();
  for (const auto& [name, value] : r.decodeSettings)
    j.beginObject().key("name").value(name).key("value").value(value).endObject();
  j.endArray().key("preprocessing").beginArray();
  for (const run::PlannedStage& p : r.preprocessing) {
    j.beginObject().key("component").value(p.component).key("parameters").beginArray();
    for (const auto& [name, value] : p.params)
      j.beginObject().key("name").value(name).key("value").value(value).endObject();
    j.endArray().endObject();
  }
  j.endArray().key("options").beginArray();
  for (const run::RunRequest::StageParam& p : r.stageParams)
    j.beginObject().key("component").value(p.component).key("name").value(p.name).key("value").value(p.value).endObject();
  j.endArray().key("webCopy");
  if (!ch.webCopy) {
    j.null();
  } else {
    j.beginObject().key("models").beginArray();
    for (const std::string& m : ch.webModels) j.value(m);
    j.endArray().key("parameters").beginArray();
    for (const carrier::Param& p : ch.webCopy->params)
      if (p.name != "model") j.beginObject().key("name").value(p.name).key("value").value(p.value).endObject();
    j.endArray().endObject();
  }
  j.endObject();
}

// The carrier as a JSON object, written into `j` (alone, or nested in a capture's object).
void carrierJson(JsonWriter& j, const carrier::Carrier& c) {
  int images = 0;
  for (const carrier::FileRecord& f : c.files) images += f.imageSize.has_value();
  j.beginObject().key("kind").value("carrier").key("title").value(c.header.title)
      .key("created").value(c.header.created).key("modified").value(c.header.modified)
      .key("rights").value(c.header.rights).key("license").value(c.header.license)
      .key("metadata").beginArray();
  for (const auto& [name, value] : c.header.meta)
    j.beginObject().key("name").value(name).key("value").value(value).endObject();
  j.endArray().key("files").value(static_cast<int>(c.files.size()))
      .key("images").value(images).key("steps").beginArray();
  for (const carrier::Step& s : c.process) {
    const carrier::Result* r = c.findResult(s.id);
    j.beginObject().key("id").value(s.id).key("component").value(s.component)
        .key("version").value(s.version).key("status").value(r ? r->status : "not run")
        .key("seconds").value(r ? r->seconds : 0.0)
        .key("interventions").value(static_cast<int>(s.interventions.size())).endObject();
  }
  j.endArray();
  choicesJson(j, c);
  j.key("creators").beginArray();
  for (const carrier::Creator& cr : c.header.creators)
    j.beginObject().key("name").value(cr.name).key("role").value(cr.role).endObject();
  j.endArray().key("decisions").beginArray();
  for (const carrier::Step& s : c.process)
    for (const carrier::Intervention& i : s.interventions)
      j.beginObject().key("step").value(s.id).key("component").value(s.component)
          .key("kind").value(i.kind).key("target").value(i.target).key("value").value(i.value)
          .key("what").value(interventionWhat(i))
          .key("who").value(i.who).key("time").value(i.time).key("reason").value(i.reason).endObject();
  j.endArray().key("exclusions").beginArray();
  for (const carrier::Step& s : c.process)
    for (const carrier::Intervention* i : s.interventionsOfKind("exclude-image"))
      j.beginObject().key("image").value(i->target).key("who").value(i->who).key("time").value(i->time)
          .key("reason").value(i->reason).endObject();
  j.endArray().key("runs").beginArray();
  for (const carrier::RunRecord& r : c.header.runs) {
    j.beginObject().key("id").value(r.id).key("command").value(r.command).key("who").value(r.who)
        .key("started").value(r.started).key("ended").value(r.ended).key("outcome").value(r.outcome)
        .key("arguments").beginArray();
    for (const std::string& a : r.arguments) j.value(a);
    j.endArray().key("notes").beginArray();
    for (const std::string& n : r.notes) j.value(n);
    j.endArray().endObject();
  }
  j.endArray().endObject();
}

// The processing choices, as text: what a run without options repeats.
void printChoices(const carrier::Carrier& c) {
  std::string why;
  const std::optional<Choices> readable = readableChoices(c, &why);
  if (!readable) {
    std::cout << "  processing choices: not readable by this version of Surrogate (" << why << ")\n";
    return;
  }
  const Choices& ch = *readable;
  const run::RunRequest& r = ch.standing;
  std::cout << "  processing choices (a run without options repeats them):\n"
            << "    image source: " << (r.source.empty() ? "auto" : r.source) << "\n";
  if (r.bases) std::cout << "    models: " << joined(*r.bases) << "\n";
  for (const auto& [name, value] : r.decodeSettings) std::cout << "    LibRaw " << name << " = " << value << "\n";
  for (const run::PlannedStage& p : r.preprocessing)
    std::cout << "    pre-processing " << p.component << ": " << paramsText(p.params) << "\n";
  for (const run::RunRequest::StageParam& p : r.stageParams)
    std::cout << "    " << p.component << " " << p.name << " = " << shownValue(p.value) << "\n";
  if (!ch.webCopy) {
    std::cout << "    web copy: none (run --publish makes one of each model)\n";
    return;
  }
  std::vector<std::pair<std::string, std::string>> options;
  for (const carrier::Param& p : ch.webCopy->params)
    if (p.name != "model") options.emplace_back(p.name, p.value);
  std::cout << "    web copy of " << joined(ch.webModels) << " in finished-files/web/ (" << paramsText(options)
            << "); run --no-publish withdraws it\n";
}

// The standing decisions (human interventions: what, in which step, who, when and why), the
// excluded images and the run history, as text.
void printDecisionsAndRuns(const carrier::Carrier& c) {
  std::cout << "  standing decisions:";
  int n = 0;
  std::string excluded;
  for (const carrier::Step& s : c.process) {
    for (const carrier::Intervention& i : s.interventions) {
      std::cout << "\n    " << i.kind << " " << i.target << " (" << s.id << " " << s.component << "): " << interventionWhat(i) << "\n      by "
                << i.who << ", " << i.time << ": " << i.reason;
      ++n;
      if (i.kind == "exclude-image") excluded += (excluded.empty() ? "" : ", ") + i.target;
    }
  }
  for (const carrier::Step& s : c.process)
    if (s.component == "CaptureIngest" && s.hasParam("lp"))
      std::cout << "\n    lights from " << s.param("lp") << " (dome capture)", ++n;
  std::cout << (n ? "\n" : " none\n");
  std::cout << "  excluded images: " << (excluded.empty() ? "none" : excluded) << "\n";
  printChoices(c);
  if (c.header.runs.empty()) return;
  std::cout << "  runs:\n";
  for (const carrier::RunRecord& r : c.header.runs) {
    std::string args;
    for (const std::string& a : r.arguments) args += " " + (a.find(' ') != std::string::npos || a.empty() ? "\"" + a + "\"" : a);
    std::cout << "    " << r.id << " " << r.started << " " << r.who << ": surrogate " << r.command
              << args << " -> " << r.outcome << "\n";
    for (const std::string& note : r.notes) std::cout << "      " << note << "\n";
  }
}

// The carrier as text: title, who made it when, rights and metadata, files, the steps with
// their status, the standing decisions and the runs.
void printCarrierText(const carrier::Carrier& c) {
  int images = 0;
  for (const carrier::FileRecord& f : c.files) images += f.imageSize.has_value();
  std::cout << "  title:   " << c.header.title << "\n"
            << "  created: " << c.header.created << " on " << c.header.machine.hostname << "\n";
  for (const carrier::Creator& cr : c.header.creators)
    std::cout << "  " << cr.role << ": " << cr.name << "\n";
  if (!c.header.rights.empty()) std::cout << "  rights:  " << c.header.rights << "\n";
  if (!c.header.license.empty()) std::cout << "  licence: " << c.header.license << "\n";
  for (const auto& [name, value] : c.header.meta) std::cout << "  metadata: " << name << " = " << value << "\n";
  std::cout << "  files:   " << c.files.size() << " (" << images << " images)\n  steps:\n";
  for (const carrier::Step& s : c.process) {
    const carrier::Result* r = c.findResult(s.id);
    std::cout << "    " << s.id << " " << s.component << " v" << s.version << ": "
              << (r ? r->status : "not run");
    if (r && r->status == "completed") std::cout << " in " << fixedDecimals(r->seconds, 1) << " s";
    if (!s.interventions.empty())
      std::cout << ", " << s.interventions.size() << (s.interventions.size() == 1 ? " decision" : " decisions")
                << " (below)";
    std::cout << "\n";
  }
  printDecisionsAndRuns(c);
}

void printCarrier(const fs::path& path, bool json) {
  const carrier::Carrier c = carrier::loadCarrier(path);
  if (json) {
    JsonWriter j;
    carrierJson(j, c);
    std::cout << j.str() << "\n";
    return;
  }
  std::cout << path.string() << ": Surrogate carrier\n";
  printCarrierText(c);
}

// --- packages (a bag folder, .tar or .zip) ---

// Whether `path` is a package: a folder with bagit.txt, or a .tar or .zip file.
bool isPackage(const fs::path& path, const fs::file_status& st) {
  std::error_code ec;
  if (fs::is_directory(st)) return fs::exists(path / "bagit.txt", ec);
  const std::string ext = lowerCase(path.extension().string());
  return fs::is_regular_file(st) && (ext == ".tar" || ext == ".zip");
}

// A path as one shell word: as it is when it needs no quoting, else in single quotes; never
// starting with '-', which would read as an option.
std::string shellWord(const std::string& path) {
  const std::string s = !path.empty() && path[0] == '-' ? "./" + path : path;
  const bool plain = !s.empty() && s.find_first_not_of(
      "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789._/+-:,@%=") == std::string::npos;
  if (plain) return s;
  std::string out = "'";
  for (char c : s) out += c == '\'' ? std::string("'\\''") : std::string(1, c);
  return out + "'";
}

// What a package's file is for: the carrier's role for the files it records, else the
// package's layout (docs/package.md); in a bag another tool made, payload or bag file.
std::string roleOf(const std::string& path, const std::map<std::string, std::string>& carrierRoles,
                   bool surrogate) {
  if (!surrogate) return path.compare(0, 5, "data/") == 0 ? "payload" : "bag files";
  if (path == "data/assembly-files/carrier.xml") return "carrier";
  if (path.compare(0, 5, "data/") == 0) {
    const auto it = carrierRoles.find(path.substr(5));
    if (it != carrierRoles.end()) {
      const std::string& r = it->second;
      if (r == "original" || r == "sidecar") return "originals";
      if (r == "export") return "exports";
      if (r == "result") return "results";
      if (r == "assembly" || r == "lp") return "assembly";
      if (r == "prior") return "prior work";  // made by another tool, found in the output folders
      return "other payload";
    }
    const std::string rest = path.substr(5);
    if (rest.compare(0, 18, "original-captures/") == 0) return "originals";
    if (rest.compare(0, 13, "jpeg-exports/") == 0) return "exports";
    if (rest.compare(0, 15, "finished-files/") == 0) return "results";
    if (rest.compare(0, 15, "assembly-files/") == 0) return "assembly";
    return "other payload";
  }
  if (path.compare(0, 9, "metadata/") == 0) return "metadata";
  return "bag files";
}

struct RoleTotal {
  std::size_t files = 0;
  std::uint64_t bytes = 0;
};

// What info shows of a package, gathered once for text and JSON.
struct PackageSummary {
  std::string kind;  // directory, tar, zip
  bool surrogate = false;
  std::vector<std::pair<std::string, std::string>> bagInfo;
  std::vector<std::string> manifests;  // manifest-sha256.txt, ...
  std::vector<std::pair<std::string, RoleTotal>> roles;  // in the order of kRoleOrder
  std::vector<std::pair<std::string, std::uint64_t>> results;  // finished files, by path
  std::uint64_t totalBytes = 0;
  std::size_t totalFiles = 0;
  std::optional<carrier::Carrier> recorded;
  std::string carrierProblem;  // why the carrier could not be read
  std::vector<std::string> verifyCommands;
};

PackageSummary summarizePackage(const fs::path& path) {
  const archive::Inventory inv = archive::readPackage(path, archive::Limits{});
  PackageSummary s;
  s.kind = inv.kind;
  const auto carrierFile = inv.files.find("data/assembly-files/carrier.xml");
  std::map<std::string, std::string> carrierRoles;
  if (carrierFile != inv.files.end()) {
    if (!carrierFile->second.content) {
      s.carrierProblem = "too large to read";
    } else {
      try {
        s.recorded = carrier::parseCarrier(*carrierFile->second.content, "data/assembly-files/carrier.xml");
        for (const carrier::FileRecord& f : s.recorded->files) carrierRoles[f.path] = f.role;
      } catch (const Error& e) {
        s.carrierProblem = e.text();
      }
    }
  }
  const auto info = inv.files.find("bag-info.txt");
  if (info != inv.files.end() && info->second.content) {
    // bag-info.txt in the encoding bagit.txt names (older bags: UTF-16, ISO-8859-1).
    std::string encoding = "UTF-8";
    if (const auto decl = inv.files.find("bagit.txt"); decl != inv.files.end() && decl->second.content) {
      const archive::Declaration d = archive::parseDeclaration(*decl->second.content);
      if (!d.encoding.empty()) encoding = d.encoding;
    }
    std::string why;
    if (const auto text = archive::decodeTagText(*info->second.content, encoding, &why))
      s.bagInfo = archive::parseBagInfo(*text).fields;
  }
  for (const auto& [label, value] : s.bagInfo)
    if (lowerCase(label) == "surrogate-package-identifier") s.surrogate = true;
  s.surrogate = s.surrogate || carrierFile != inv.files.end();

  static const char* kRoleOrder[] = {"originals", "exports", "assembly", "carrier", "results",
                                     "prior work", "other payload", "payload", "metadata", "bag files"};
  std::map<std::string, RoleTotal> totals;
  for (const auto& [file, f] : inv.files) {
    if (archive::manifestName(file) && archive::manifestName(file)->first == "manifest")
      s.manifests.push_back(file);
    const std::string role = roleOf(file, carrierRoles, s.surrogate);
    totals[role].files += 1;
    totals[role].bytes += f.size;
    s.totalFiles += 1;
    s.totalBytes += f.size;
    if (role == "results") s.results.emplace_back(file.substr(5), f.size);
  }
  for (const char* role : kRoleOrder)
    if (totals.count(role)) s.roles.emplace_back(role, totals[role]);
  const std::string word = shellWord(path.string());
  s.verifyCommands.push_back("surrogate verify " + word);
  if (s.surrogate) s.verifyCommands.push_back("surrogate verify " + word + " --reexecute");
  return s;
}

std::string bagInfoValue(const PackageSummary& s, const std::string& label) {
  for (const auto& [k, v] : s.bagInfo)
    if (lowerCase(k) == lowerCase(label)) return v;
  return "";
}

void printPackageJson(const PackageSummary& s) {
  JsonWriter j;
  j.beginObject().key("kind").value("package").key("format").value(s.kind)
      .key("surrogatePackage").value(s.surrogate)
      .key("files").value(static_cast<unsigned long long>(s.totalFiles))
      .key("bytes").value(static_cast<unsigned long long>(s.totalBytes));
  j.key("bagInfo").beginArray();
  for (const auto& [label, value] : s.bagInfo)
    j.beginObject().key("label").value(label).key("value").value(value).endObject();
  j.endArray().key("manifests").beginArray();
  for (const std::string& m : s.manifests) j.value(m);
  j.endArray().key("roles").beginArray();
  for (const auto& [role, t] : s.roles)
    j.beginObject().key("role").value(role).key("files").value(static_cast<unsigned long long>(t.files))
        .key("bytes").value(static_cast<unsigned long long>(t.bytes)).endObject();
  j.endArray().key("results").beginArray();
  for (const auto& [file, bytes] : s.results)
    j.beginObject().key("path").value(file).key("bytes").value(static_cast<unsigned long long>(bytes)).endObject();
  j.endArray();
  if (s.recorded) {
    j.key("carrier");
    carrierJson(j, *s.recorded);
  } else if (!s.carrierProblem.empty()) {
    j.key("carrierProblem").value(s.carrierProblem);
  }
  j.key("verify").beginArray();
  for (const std::string& c : s.verifyCommands) j.value(c);
  j.endArray().endObject();
  std::cout << j.str() << "\n";
}

void printPackageText(const fs::path& path, const PackageSummary& s) {
  std::cout << path.string() << ": " << (s.surrogate ? "Surrogate package" : "BagIt bag, not a Surrogate package")
            << " (" << s.kind << ")\n";
  if (s.surrogate) {
    std::cout << "  identifier: " << bagInfoValue(s, "Surrogate-Package-Identifier") << "\n"
              << "  packed:     " << bagInfoValue(s, "Surrogate-Packaging-Time") << " by "
              << bagInfoValue(s, "Bag-Software-Agent") << "\n";
  } else {
    for (const auto& [label, value] : s.bagInfo)
      std::cout << "  " << label << ": " << value << "\n";
  }
  std::cout << "  holds:      " << s.totalFiles << " files, " << archive::humanSize(s.totalBytes)
            << " (manifests:";
  for (const std::string& m : s.manifests) std::cout << " " << m;
  std::cout << ")\n";
  for (const auto& [role, t] : s.roles) {
    std::string name = role;
    name.resize(14, ' ');
    std::cout << "    " << name << t.files << (t.files == 1 ? " file,  " : " files, ")
              << archive::humanSize(t.bytes) << "\n";
  }
  if (!s.results.empty()) {
    std::cout << "  results:\n";
    for (const auto& [file, bytes] : s.results)
      std::cout << "    " << file << "  " << archive::humanSize(bytes) << "\n";
  }
  if (s.recorded) {
    std::cout << "  carrier (data/assembly-files/carrier.xml):\n";
    printCarrierText(*s.recorded);
  } else if (!s.carrierProblem.empty()) {
    std::cout << "  carrier:    cannot be read: " << s.carrierProblem << "\n";
  }
  std::cout << "  to verify it:\n";
  for (const std::string& c : s.verifyCommands) std::cout << "    " << c << "\n";
}

void printPackage(const fs::path& path, bool json) {
  const PackageSummary s = summarizePackage(path);
  if (json) printPackageJson(s);
  else printPackageText(path, s);
}

// How the shots are held: "8 originals in original-captures/, 8 JPEG exports"; for a capture
// of JPEG exports alone, the exports are the originals the pipeline reads (docs/user-guide.md).
std::string shotsText(const capture::CaptureLayout& layout, int originals, int exports) {
  if (!layout.hasOriginals())
    return "exports in " + std::string(capture::kExportsDir) + "/, no raw originals: the exports "
           "are the originals the pipeline reads";
  return std::to_string(originals) + " originals in " + layout.originalsDir + "/" +
         (exports ? ", " + std::to_string(exports) + " exports in " + capture::kExportsDir + "/" : "");
}

// A capture folder; with --json, a processed capture's carrier is nested under "carrier".
void printCapture(const fs::path& path, bool json) {
  // A dome capture's .lp is a decision the carrier records (`run --lp`).
  const fs::path carrierPath = path / capture::kAssemblyDir / "carrier.xml";
  std::string domeLp;
  if (fs::exists(carrierPath))
    for (const carrier::Step& s : carrier::loadCarrier(carrierPath).process)
      if (s.component == "CaptureIngest") domeLp = s.param("lp", "");
  const capture::CaptureLayout layout = capture::scanCapture(path, 0, domeLp);
  int originals = 0, exports = 0;
  for (const capture::Shot& s : layout.shots) {
    originals += s.original.has_value();
    exports += s.exported.has_value();
  }
  const capture::Shot& first = layout.shots.front();
  const capture::ImageFile& sample = first.original ? *first.original : *first.exported;
  if (json) {
    JsonWriter j;
    j.beginObject().key("kind").value("capture").key("shots").value(static_cast<int>(layout.shots.size()))
        .key("originals").value(originals).key("exports").value(exports)
        // What the carrier records as the originals: the exports, in a capture of exports alone.
        .key("originalsFolder").value((layout.hasOriginals() ? layout.originalsDir : std::string(capture::kExportsDir)) + "/")
        .key("width").value(sample.width).key("height").value(sample.height)
        .key("lp").value(layout.lp.value_or(""));
    if (fs::exists(carrierPath)) {
      j.key("carrier");
      carrierJson(j, carrier::loadCarrier(carrierPath));
    }
    j.endObject();
    std::cout << j.str() << "\n";
    return;
  }
  std::cout << path.string() << ": capture folder\n"
            << "  shots:     " << layout.shots.size() << " (" << shotsText(layout, originals, exports) << ")\n"
            << "  image:     " << sample.width << "x" << sample.height << " " << sample.format << "\n"
            << "  lights:    " << (layout.lp ? "given by " + *layout.lp + " (dome capture)" : "to be detected from the spheres")
            << "\n";
  for (const std::string& other : layout.others)
    if (other.find('/') == std::string::npos && lowerCase(fs::path(other).extension().string()) == ".lp")
      std::cout << "  note:      " << other << " is kept as a file of the capture but not used; for "
                << "a dome capture whose lights it gives, run with --lp " << other << "\n";
}

// --- images and sidecars ---

// What info shows of an image, gathered once for text and JSON: its metadata (Exiv2) and
// whether Surrogate decodes it. A camera format LibRaw does not decode (CR3, some DNGs) still
// has its metadata described; the refusal is stated on its own line.
struct ImageSummary {
  std::optional<image::ImageProbe> probe;
  std::string decodeProblem;  // why the pixels cannot be decoded
  std::optional<meta::CameraMetadata> camera;
  std::string metadataProblem;
};

ImageSummary summarizeImage(const fs::path& path) {
  ImageSummary s;
  std::optional<Error> refusal;
  try {
    s.probe = image::probeImage(path);
  } catch (const Error& e) {
    s.decodeProblem = e.message();
    refusal = e;
  }
  try {
    s.camera = meta::readMetadata(path);
  } catch (const Error& e) {
    if (refusal) throw *refusal;  // neither pixels nor metadata: not an image Surrogate reads
    s.metadataProblem = e.message();
  }
  return s;
}

const char* kindName(image::SourceKind kind) {
  switch (kind) {
    case image::SourceKind::CameraRaw: return "camera raw";
    case image::SourceKind::Jpeg: return "JPEG";
    case image::SourceKind::Tiff: return "TIFF";
    case image::SourceKind::Png: return "PNG";
  }
  return "image";
}

// The camera metadata as JSON members: every field the carrier records under <camera>, with
// numbers as numbers and the date in ISO 8601, and `shown`, the text `info` prints.
void cameraJson(JsonWriter& j, const meta::CameraMetadata& m) {
  auto text = [&](const char* k, const std::optional<std::string>& v) {
    if (v && !v->empty()) j.key(k).value(*v);
  };
  auto number = [&](const char* k, const auto& v) {
    if (v) j.key(k).value(static_cast<double>(*v));
  };
  text("make", m.make);
  text("model", m.model);
  text("serial", m.bodySerial);
  text("lens", m.lens);
  if (m.lens) j.key("lensFromMakerNote").value(m.lensFromMakerNote);
  if (m.lensMinFocalMm && m.lensMaxFocalMm)
    j.key("lensFocalRangeMm").beginArray().value(*m.lensMinFocalMm).value(*m.lensMaxFocalMm).endArray();
  number("focalLengthMm", m.focalLengthMm);
  number("fNumber", m.fNumber);
  text("exposureTime", m.exposureTime);
  number("exposureSeconds", m.exposureSeconds);
  number("iso", m.iso);
  if (m.dateTimeOriginal) j.key("dateTimeOriginal").value(meta::dateTimeText(*m.dateTimeOriginal, m.offsetTimeOriginal));
  text("offsetTimeOriginal", m.offsetTimeOriginal);
  number("orientation", m.orientation);
  number("pixelWidth", m.pixelWidth);
  number("pixelHeight", m.pixelHeight);
  number("focalPlaneXResolution", m.focalPlaneXResolution);
  number("focalPlaneYResolution", m.focalPlaneYResolution);
  number("focalPlaneResolutionUnit", m.focalPlaneResolutionUnit);
  j.key("xmp").value(!m.xmpPacket.empty()).key("xmpBytes").value(static_cast<unsigned long long>(m.xmpPacket.size()));
  j.key("shown").beginObject();
  auto shown = [&](const char* k, const std::string& v) {
    if (!v.empty()) j.key(k).value(v);
  };
  shown("camera", meta::cameraText(m));
  shown("lens", meta::lensText(m));
  if (m.focalLengthMm) shown("focalLength", meta::focalLengthText(*m.focalLengthMm));
  if (m.fNumber) shown("aperture", meta::apertureText(*m.fNumber));
  if (m.exposureSeconds) shown("exposure", meta::exposureText(*m.exposureSeconds));
  if (m.dateTimeOriginal) shown("taken", meta::dateTimeText(*m.dateTimeOriginal, m.offsetTimeOriginal));
  j.endObject();
}

void printImageJson(const ImageSummary& s) {
  JsonWriter j;
  j.beginObject().key("kind").value("image").key("decodable").value(s.probe.has_value());
  if (s.probe)
    j.key("width").value(s.probe->width).key("height").value(s.probe->height)
        .key("format").value(kindName(s.probe->kind));
  else
    j.key("decodeProblem").value(s.decodeProblem);
  if (s.camera) cameraJson(j, *s.camera);
  else j.key("metadataProblem").value(s.metadataProblem);
  j.endObject();
  std::cout << j.str() << "\n";
}

// "31 mm, f/5.6, 1/125 s, ISO 100": the exposure as a photographer notes it, known parts only.
std::string exposureLine(const meta::CameraMetadata& m) {
  std::string line;
  auto add = [&](const std::string& part) {
    if (!part.empty()) line += (line.empty() ? "" : ", ") + part;
  };
  if (m.focalLengthMm) add(meta::focalLengthText(*m.focalLengthMm));
  if (m.fNumber) add(meta::apertureText(*m.fNumber));
  if (m.exposureSeconds) add(meta::exposureText(*m.exposureSeconds));
  else if (m.exposureTime) add(*m.exposureTime);
  if (m.iso) add("ISO " + std::to_string(*m.iso));
  return line;
}

void printCameraText(const meta::CameraMetadata& m) {
  auto line = [](const char* label, const std::string& value) {
    if (!value.empty()) std::cout << "  " << label << value << "\n";
  };
  const std::string camera = meta::cameraText(m);
  line("camera:      ", camera + (m.bodySerial ? (camera.empty() ? "serial " : ", serial ") + *m.bodySerial : ""));
  line("lens:        ", meta::lensText(m));
  line("exposure:    ", exposureLine(m));
  if (m.dateTimeOriginal) line("taken:       ", meta::dateTimeText(*m.dateTimeOriginal, m.offsetTimeOriginal));
  if (m.pixelWidth && m.pixelHeight)
    line("EXIF size:   ", std::to_string(*m.pixelWidth) + "x" + std::to_string(*m.pixelHeight));
  if (m.orientation)
    line("orientation: ", std::to_string(*m.orientation) + " (" + meta::orientationText(*m.orientation) + ")");
  if (m.focalPlaneXResolution) {
    const std::string x = fixedDecimals(*m.focalPlaneXResolution, 1);
    const std::string y = m.focalPlaneYResolution ? fixedDecimals(*m.focalPlaneYResolution, 1) : x;
    line("focal plane: ", (x == y ? x : x + " x " + y) + " " +
                              meta::resolutionUnitText(m.focalPlaneResolutionUnit.value_or(2)));
  }
  line("XMP:         ", m.xmpPacket.empty() ? "none" : std::to_string(m.xmpPacket.size()) + " bytes");
}

void printImage(const fs::path& path, bool json) {
  const ImageSummary s = summarizeImage(path);
  if (json) return printImageJson(s);
  std::cout << path.string() << ": ";
  if (s.probe)
    std::cout << "image " << s.probe->width << "x" << s.probe->height << ", " << kindName(s.probe->kind) << "\n";
  else
    std::cout << "image whose metadata Surrogate reads but whose pixels it cannot decode\n";
  if (s.camera) printCameraText(*s.camera);
  else std::cout << "  metadata:    cannot be read: " << s.metadataProblem << "\n";
  if (!s.probe) std::cout << "  decoding:    refused: " << s.decodeProblem << "\n";
}

// An .xmp sidecar: what it records about its image, not the image itself.
void printXmpSidecar(const fs::path& path, bool json) {
  const meta::XmpSidecarSummary s = meta::summarizeXmpSidecar(path);
  if (json) {
    JsonWriter j;
    j.beginObject().key("kind").value("xmp-sidecar").key("bytes").value(static_cast<unsigned long long>(s.bytes));
    auto text = [&](const char* k, const std::optional<std::string>& v) {
      if (v && !v->empty()) j.key(k).value(*v);
    };
    text("software", s.creatorTool);
    text("rating", s.rating);
    text("modified", s.modified);
    text("creator", s.creator);
    text("rights", s.rights);
    j.key("developSettings").value(s.developSettings);
    text("processVersion", s.processVersion);
    j.key("history").beginArray();
    for (const meta::XmpHistoryEvent& e : s.history)
      j.beginObject().key("action").value(e.action).key("when").value(e.when)
          .key("software").value(e.software).key("changed").value(e.changed).endObject();
    j.endArray().endObject();
    std::cout << j.str() << "\n";
    return;
  }
  auto line = [](const char* label, const std::optional<std::string>& v) {
    if (v && !v->empty()) std::cout << "  " << label << *v << "\n";
  };
  std::cout << path.string() << ": XMP sidecar (metadata kept next to an image, " << s.bytes
            << " bytes; Surrogate records it verbatim with its original)\n";
  line("written by:  ", s.creatorTool);
  line("modified:    ", s.modified);
  line("rating:      ", s.rating ? std::optional<std::string>(*s.rating == "-1" ? "rejected" : *s.rating + " of 5") : std::nullopt);
  line("creator:     ", s.creator);
  line("rights:      ", s.rights);
  std::cout << "  develop:     "
            << (s.developSettings ? std::to_string(s.developSettings) + " Camera Raw / Lightroom settings" +
                                        (s.processVersion ? " (process version " + *s.processVersion + ")" : "")
                                  : "no develop settings")
            << "\n";
  std::cout << "  history:     " << (s.history.empty() ? "none recorded" : std::to_string(s.history.size()) + " event(s)") << "\n";
  for (const meta::XmpHistoryEvent& e : s.history) {
    std::cout << "    " << (e.when.empty() ? "-" : e.when) << " " << e.action;
    if (!e.changed.empty()) std::cout << " (" << e.changed << ")";
    if (!e.software.empty()) std::cout << " by " << e.software;
    std::cout << "\n";
  }
}

// A web layout (publish/web_layout.h): what its info.json says and whether its planes are there.
void printWebLayout(const fs::path& path, bool json) {
  const publish::WebLayoutSummary s = publish::describeWebLayout(path);
  if (json) {
    JsonWriter j;
    j.beginObject().key("kind").value("web-layout").key("type").value(s.type).key("colorspace").value(s.colorspace)
        .key("basis").value(s.basis).key("width").value(s.width).key("height").value(s.height)
        .key("nplanes").value(s.nplanes).key("format").value(s.format);
    if (s.quality >= 0) j.key("quality").value(s.quality);
    j.key("planes").beginArray();
    for (const std::string& p : s.planes) j.value(p);
    j.endArray().key("missingPlanes").beginArray();
    for (const std::string& p : s.missingPlanes) j.value(p);
    j.endArray();
    if (!s.tiles.empty()) j.key("tiles").value(s.tiles);
    j.key("bytes").value(static_cast<unsigned long long>(s.bytes)).endObject();
    std::cout << j.str() << "\n";
    return;
  }
  std::cout << path.string() << ": web layout (OpenLIME, relight)\n"
            << "  model:   " << s.type << " " << s.colorspace << (s.basis.empty() ? "" : " (" + s.basis + ")") << ", "
            << s.width << "x" << s.height << ", " << s.nplanes << " coefficients per texel\n"
            << "  planes:  " << s.planes.size() << " " << s.format << " images"
            << (s.tiles.empty() ? std::string() : " (" + s.tiles + " tiles)")
            << (s.quality >= 0 ? ", quality " + std::to_string(s.quality) : std::string()) << ", " << s.bytes
            << " bytes with info.json\n";
  for (const std::string& p : s.missingPlanes) std::cout << "  missing: " << p << " (the viewers cannot show the model)\n";
}

// The folder `surrogate publish` writes for one model: an info.json, and none of a capture's
// folders (a capture is described as one even if someone left an info.json in it).
bool isWebLayoutFolder(const fs::path& path) {
  std::error_code ec;
  return fs::is_regular_file(path / "info.json", ec) && !fs::exists(path / capture::kAssemblyDir, ec) &&
         !fs::exists(path / "original-captures", ec) && !fs::exists(path / capture::kExportsDir, ec);
}

}  // namespace

int runCommandInfo(int argc, char** argv) {
  const std::vector<OptionSpec> specs = {{"json", false, false, "print as JSON"}};
  Args args(argc, argv, 1, specs);
  if (args.helpRequested()) {
    std::cout << usageHeader("surrogate info FILE",
                             "Describe a package (a bag folder, .tar or .zip: what it holds by "
                             "role, who made it when, the steps, decisions and results, and the "
                             "command to verify it), a carrier (carrier.xml: creators, metadata, "
                             "steps, decisions with who, when and why, runs), a capture folder, "
                             "an image (camera, lens, exposure, date; also one Surrogate cannot "
                             "decode), an .xmp sidecar, a .ptm, .rti or .lp file, RTIBuilder's log "
                             "XML (what its processing used and found), or a web layout "
                             "(the folder surrogate publish writes, or its info.json).")
              << Args::describe(specs);
    return 0;
  }
  if (args.positional().size() != 1)
    throw Error(ErrorKind::Usage, "", "command line", "give one file or folder: surrogate info FILE");
  const fs::path path = args.positional()[0];
  const bool json = args.has("json");
  // Error codes, not exceptions: a loop of symbolic links is the user's path, not a bug.
  std::error_code ec;
  const fs::file_status st = fs::status(path, ec);
  if (ec == std::errc::too_many_symbolic_link_levels)
    throwInputError(path.string(), "info", "is a loop of symbolic links; give the file or folder itself");
  if (!fs::exists(st)) throwInputError(path.string(), "info", "does not exist");
  const std::string ext = lowerCase(path.extension().string());
  if (isPackage(path, st)) {
    printPackage(path, json);
  } else if (fs::is_directory(st) && isWebLayoutFolder(path)) {
    printWebLayout(path / "info.json", json);
  } else if (fs::is_directory(st)) {
    if (fs::exists(path / capture::kAssemblyDir / "carrier.xml", ec) && !json) {
      printCapture(path, false);
      printCarrier(path / capture::kAssemblyDir / "carrier.xml", false);  // JSON: nested by printCapture
    } else {
      printCapture(path, json);
    }
  } else if (path.filename() == "info.json") {
    printWebLayout(path, json);
  } else if (ext == ".xml" && audit::looksLikeRtiBuilderLog(path)) {
    const audit::RtiBuilderLog log = audit::readRtiBuilderLog(path);
    std::cout << (json ? log.toJson() : log.toText()) << "\n";
  } else if (ext == ".xml") {
    printCarrier(path, json);
  } else if (ext == ".xmp") {
    printXmpSidecar(path, json);
  } else if (ext == ".ptm" || ext == ".rti" || ext == ".lp") {
    const formats::FileSummary s = formats::summarize(path);
    std::cout << (json ? s.toJson() : s.toText()) << "\n";
  } else {
    printImage(path, json);
  }
  return 0;
}

}  // namespace surrogate::cli
