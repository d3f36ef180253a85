// package.*: a Surrogate package is complete (every file `surrogate pack` writes is there), its
// bundled stylesheets, schemas and mapping tables are the ones this verifier bundles, and the
// fields of its bag-info.txt that Surrogate writes are what packing the carrier gives (any
// other field is the holder's, listed).
#include <mutex>
#include <regex>
#include <set>

#include "archive/bag.h"
#include "archive/bag_text.h"
#include "archive/package.h"
#include "archive/package_readme.h"
#include "capture/capture.h"
#include "carrier/carrier.h"
#include "core/atomic_file.h"
#include "core/digest.h"
#include "core/error.h"
#include "core/resources.h"
#include "core/text.h"
#include "core/version.h"
#include "mapping/mapping.h"
#include "verify/checks.h"

namespace surrogate::verify {

namespace {

// The SHA-256 of each resource this verifier bundles, by bag path ("metadata/xsd/..."),
// computed once per process.
const std::map<std::string, std::string>& bundledDigests() {
  static std::once_flag once;
  static std::map<std::string, std::string> digests;
  std::call_once(once, [] {
    for (const std::string& path : archive::packageMetadataFiles()) {
      if (path == "metadata/crm.rdf" || path == "metadata/mets.xml") continue;  // derived
      // The documents explain the package to a reader; nothing is checked or derived with
      // them, so a package keeps verifying when a later build words them differently (the
      // tag manifests hold them fixed like every tag file): documentWarnings.
      if (path.rfind("metadata/docs/", 0) == 0) continue;
      const std::string rel = path.substr(std::string("metadata/").size());
      digests[path] = sha256Hex(readFile(resourcePath(rel), "verify"));
    }
  });
  return digests;
}

// The tag files every Surrogate package has (bagit.txt, bag-info.txt, both manifests and tag
// manifests, metadata/...), sorted.
std::vector<std::string> requiredTagFiles() {
  std::vector<std::string> out = {"bag-info.txt",          "bagit.txt",
                                  "manifest-sha256.txt",   "manifest-sha512.txt",
                                  "tagmanifest-sha256.txt", "tagmanifest-sha512.txt",
                                  archive::kReadmePath};
  for (const std::string& p : archive::packageMetadataFiles()) out.push_back(p);
  std::sort(out.begin(), out.end());
  return out;
}

// The first value of a bag-info.txt label, or "" (package.info judges repeated or missing ones).
std::string firstValue(const BagInfo& info, const char* label) {
  const auto v = info.values(label);
  return v.empty() ? std::string() : v.front();
}

std::string softwareAgentOf(const Inventory& inv) {
  const std::string* text = contentOf(inv, "bag-info.txt");
  return text ? firstValue(parseBagInfo(*text), "Bag-Software-Agent") : "";
}

// A bag-info value as it reads back: line breaks folded into continuation lines, each line
// trimmed and the lines joined by one space (parseBagInfo).
std::string asReadBack(const std::string& value) {
  std::string out;
  bool first = true;
  for (const std::string& line : splitLines(value + "\n")) {
    std::size_t b = 0, e = line.size();
    while (b < e && (line[b] == ' ' || line[b] == '\t')) ++b;
    while (e > b && (line[e - 1] == ' ' || line[e - 1] == '\t')) --e;
    out += (first ? "" : " ") + line.substr(b, e - b);
    first = false;
  }
  return out;
}

// RFC 8493 2.2.2: Bag-Count is "N of T", T the total or "?" when it is not known, N <= T.
bool wellFormedBagCount(const std::string& value) {
  static const std::regex form(R"(([0-9]{1,18}) of ([0-9]{1,18}|\?))");
  std::smatch m;
  if (!std::regex_match(value, m, form)) return false;
  return m[2] == "?" || std::stoull(m[1].str()) <= std::stoull(m[2].str());
}

std::string quoted(const std::string& s) { return "\"" + s.substr(0, 200) + (s.size() > 200 ? "..." : "") + "\""; }

}  // namespace

bool isSurrogatePackage(const Inventory& inv) {
  // Any one mark of `surrogate pack` is enough: a package cut short or with files removed must
  // be judged as the Surrogate package it was (and found incomplete), never pass as a plain bag
  // from another tool because the mark that remains is not the carrier.
  if (inv.files.count(kCarrierPath)) return true;
  for (const std::string& path : archive::packageMetadataFiles())
    if (inv.files.count(path)) return true;
  // README.txt comes first in a package's byte order: a package cut after it has only it. It
  // is Surrogate's when it says it was packed by Surrogate, whatever the wrapping of its lines.
  if (const std::string* readme = contentOf(inv, archive::kReadmePath)) {
    std::string words;
    for (char ch : readme->substr(0, 4096)) {
      const bool space = ch == ' ' || ch == '\n' || ch == '\r' || ch == '\t';
      if (!space) words += ch;
      else if (!words.empty() && words.back() != ' ') words += ' ';
    }
    if (words.find("(RFC 8493) by Surrogate ") != std::string::npos) return true;
  }
  if (const std::string* text = contentOf(inv, "bag-info.txt")) {
    const BagInfo info = parseBagInfo(*text);
    if (!info.values("Surrogate-Package-Identifier").empty() ||
        !info.values("Surrogate-Packaging-Time").empty())
      return true;
    for (const std::string& agent : info.values("Bag-Software-Agent"))
      if (agent.rfind("Surrogate ", 0) == 0) return true;
  }
  return false;
}

void checkCompleteness(const Inventory& inv, std::vector<Check>& checks) {
  if (!isSurrogatePackage(inv)) return;
  // Every file `surrogate pack` writes: a package without one was cut short (a truncated
  // archive, an interrupted copy) or had files removed, and is never sound.
  std::vector<std::string> missing;
  std::vector<std::string> required = requiredTagFiles();
  required.push_back(kCarrierPath);
  required.push_back(mapping::kRoCratePath);
  for (const std::string& path : required)
    if (!inv.files.count(path))
      missing.push_back(path + ": missing; every Surrogate package has it");
  checks.push_back(makeCheck(
      "package.complete", Severity::Fixity,
      "every file of a Surrogate package is present (bagit.txt, bag-info.txt, README.txt, both "
      "manifests and tag manifests, the carrier, metadata/)",
      "the package is incomplete: it was cut short (a truncated archive or copy) or files were "
      "removed",
      missing));

  // The stylesheets, schemas and mapping tables: byte for byte the ones this verifier bundles,
  // so that what they say is what the verifier checked with; and no other tag file.
  std::vector<std::string> problems;
  const std::string agent = softwareAgentOf(inv);
  const std::string ours = std::string("Surrogate ") + surrogateVersion();
  const std::set<std::string> known(required.begin(), required.end());
  for (const auto& [path, digest] : bundledDigests()) {
    const auto it = inv.files.find(path);
    if (it == inv.files.end()) continue;  // package.complete
    if (it->second.sha256 == digest) continue;
    std::string why = path + ": differs from the " + path.substr(path.rfind('/') + 1) +
                      " this verifier bundles (SHA-256 " + it->second.sha256.substr(0, 16) +
                      "..., bundled " + digest.substr(0, 16) + "...)";
    if (!agent.empty() && agent != ours)
      why += "; the package was made by " + agent + " and this verifier is " + ours +
             ": verify it with " + agent;
    else
      why += "; it was changed after packing";
    problems.push_back(why);
  }
  for (const auto& [path, file] : inv.files) {
    if (path.compare(0, 5, "data/") == 0 || known.count(path)) continue;
    problems.push_back(path + ": not a file `surrogate pack` writes (added to the package "
                       "after packing?)");
  }
  checks.push_back(makeCheck(
      "package.bundled", Severity::Invalid,
      "the stylesheets, schemas and mapping tables in metadata/ are byte-identical to the ones "
      "this verifier bundles, and there is no other tag file (metadata/docs/ is documentation, "
      "held by the tag manifests)",
      "metadata/ holds stylesheets, schemas or tables other than this verifier's, or other "
      "files",
      problems));
}

void checkPackageInfo(const Inventory& inv, const std::optional<carrier::Carrier>& recorded,
                      std::vector<Check>& checks,
                      std::vector<std::pair<std::string, std::string>>& holderFields) {
  const std::string* text = contentOf(inv, "bag-info.txt");
  const auto carrierFile = inv.files.find(kCarrierPath);
  if (!isSurrogatePackage(inv) || !text || !recorded || carrierFile == inv.files.end()) return;
  const BagInfo info = parseBagInfo(*text);
  std::vector<std::string> problems;
  auto one = [&](const std::string& label) -> std::optional<std::string> {
    const auto v = info.values(label);
    if (v.empty()) {
      problems.push_back("bag-info.txt: " + label + " is missing");
      return std::nullopt;
    }
    if (v.size() > 1) {
      problems.push_back("bag-info.txt: " + label + " is given " + std::to_string(v.size()) +
                         " times; a package has it once");
      return std::nullopt;
    }
    return v.front();
  };

  // The labels writeBag computes.
  if (const auto agent = one("Bag-Software-Agent"); agent && agent->compare(0, 10, "Surrogate ") != 0)
    problems.push_back("bag-info.txt: Bag-Software-Agent is " + quoted(*agent) +
                       ", not Surrogate: this is not a package `surrogate pack` wrote");
  const auto oxum = one("Payload-Oxum");
  if (const auto size = one("Bag-Size"); size && oxum) {
    if (const auto parsed = parseOxum(*oxum)) {
      const std::string expected = archive::humanSize(parsed->first);
      if (*size != expected)
        problems.push_back("bag-info.txt: Bag-Size is " + quoted(*size) + ", Payload-Oxum " +
                           *oxum + " gives " + quoted(expected));
    }
  }
  const auto time = one("Surrogate-Packaging-Time");
  static const std::regex dateTime(R"(\d{4}-\d\d-\d\dT\d\d:\d\d:\d\dZ)");
  if (time && !std::regex_match(*time, dateTime))
    problems.push_back("bag-info.txt: Surrogate-Packaging-Time " + quoted(*time) +
                       " is not a UTC time YYYY-MM-DDTHH:MM:SSZ");
  if (const auto date = one("Bagging-Date"); date && time && std::regex_match(*time, dateTime) &&
                                             *date != time->substr(0, 10))
    problems.push_back("bag-info.txt: Bagging-Date " + *date + " is not the day of "
                       "Surrogate-Packaging-Time " + *time);

  // The package identifier: the SHA-256 of the carrier in the bag.
  const std::string id = archive::packageIdentifier(carrierFile->second.sha256);
  if (const auto given = one("Surrogate-Package-Identifier"); given && *given != id)
    problems.push_back("bag-info.txt: Surrogate-Package-Identifier is " + quoted(*given) +
                       "; the carrier in the package gives " + id);

  // The capture identifier: the carrier's first file's (archive::captureIdentifier).
  const std::string captureId = archive::captureIdentifier(*recorded);
  if (const auto given = one("Surrogate-Capture-Identifier"); given && *given != captureId)
    problems.push_back("bag-info.txt: Surrogate-Capture-Identifier is " + quoted(*given) +
                       "; the carrier in the package gives " + captureId);
  // The package this one revises and the base of crm.rdf's URIs: facts of the packing, not of
  // the carrier (docs/package.md, "Identifiers"); their form is checked here, and crm.rdf and
  // mets.xml must be what they give (metadata.derived).
  auto optional = [&](const char* label) -> std::string {
    const auto v = info.values(label);
    if (v.size() > 1)
      problems.push_back(std::string("bag-info.txt: ") + label + " is given " + std::to_string(v.size()) +
                         " times; a package has it once at most");
    return v.empty() ? std::string() : v.front();
  };
  const std::string previous = optional("Surrogate-Previous-Package-Identifier");
  if (!previous.empty() && (!archive::isPackageIdentifier(previous) || previous == id))
    problems.push_back("bag-info.txt: Surrogate-Previous-Package-Identifier " + quoted(previous) +
                       (previous == id ? " is this package's own identifier"
                                       : " is not a package identifier (urn:sha256: and 64 hexadecimal digits)"));
  const std::string baseUri = optional("Surrogate-Base-URI");
  if (!baseUri.empty())
    if (const std::string why = archive::baseUriProblem(baseUri); !why.empty())
      problems.push_back("bag-info.txt: Surrogate-Base-URI " + quoted(baseUri) + " " + why);

  // The user's labels: the carrier's header metadata, each as packing writes it.
  const archive::PackageInfo expected = archive::packageInfo(*recorded, id, time.value_or(""), previous, baseUri);
  for (const auto& [label, value] : expected.user) {
    const auto given = one(label);
    if (given && *given != asReadBack(value))
      problems.push_back("bag-info.txt: " + label + " is " + quoted(*given) +
                         "; the carrier's header gives " + quoted(asReadBack(value)));
  }
  // Every other field is the holder's (RFC 8493 lets a bag's holder add fields; pack
  // --bag-info writes such fields too): listed, never taken for Surrogate's. A label in
  // Surrogate's namespace that packing does not give is no holder's field but a forgery.
  std::set<std::string> reported;
  for (const auto& [label, value] : info.fields) {
    if (!archive::isSurrogateLabel(label, expected)) {
      holderFields.emplace_back(label, value);
      if (lowerCase(label) == "bag-count" && !wellFormedBagCount(value))
        problems.push_back("bag-info.txt: Bag-Count " + quoted(value) + " is not \"N of T\" "
                           "(or \"N of ?\") as RFC 8493 defines it");
    } else if (lowerCase(label).rfind("surrogate-", 0) == 0) {
      bool given = false;
      for (const auto* labels : {&expected.user, &expected.own})
        for (const auto& [l, v] : *labels) given |= lowerCase(l) == lowerCase(label);
      if (!given && reported.insert(lowerCase(label)).second)
        problems.push_back("bag-info.txt: " + label + " is a Surrogate-* label that packing the "
                           "carrier does not give (added after packing?)");
    }
  }
  checks.push_back(makeCheck(
      "package.info", Severity::Invalid,
      "the fields of bag-info.txt that Surrogate writes are what packing the carrier gives: its "
      "identifier (" + id.substr(0, 27) + "...), metadata, dates and sizes" +
          (holderFields.empty() ? std::string()
                                : "; " + std::to_string(holderFields.size()) +
                                      " more added by the holder (listed below)"),
      "bag-info.txt disagrees with the carrier", problems));
}

void checkReadme(const Inventory& inv, const carrier::Carrier& recorded, std::vector<Check>& checks) {
  const auto readme = inv.files.find(archive::kReadmePath);
  const std::string* info = contentOf(inv, "bag-info.txt");
  if (readme == inv.files.end() || !info) return;  // package.complete
  const BagInfo bagInfo = parseBagInfo(*info);
  auto one = [&](const char* label) { return firstValue(bagInfo, label); };
  archive::ReadmeFacts facts;
  facts.packageId = one("Surrogate-Package-Identifier");
  facts.packagingTime = one("Surrogate-Packaging-Time");
  facts.softwareAgent = one("Bag-Software-Agent");
  facts.previousPackageId = one("Surrogate-Previous-Package-Identifier");
  facts.baseUri = one("Surrogate-Base-URI");
  facts.hasReport = inv.files.count(std::string("data/") + capture::kReportPath) > 0;
  const std::string expected = archive::packageReadme(recorded, facts);
  std::vector<std::string> problems;
  if (readme->second.sha256 != sha256Hex(expected)) {
    const std::string* found = contentOf(inv, archive::kReadmePath);
    problems.push_back(std::string(archive::kReadmePath) + ": " +
                       (found ? firstDifference(expected, *found) : std::string("differs")) +
                       "; it was changed after packing (the tag manifests must have been redone)");
  }
  checks.push_back(makeCheck("package.readme", Severity::Invalid,
                             "README.txt says what packing the carrier writes",
                             "README.txt says what the carrier does not", problems));
}

std::vector<std::string> documentWarnings(const Inventory& inv) {
  std::vector<std::string> out;
  if (!isSurrogatePackage(inv)) return out;
  for (const std::string& rel : archive::bundledDocuments()) {
    const auto it = inv.files.find("metadata/" + rel);
    if (it == inv.files.end()) continue;  // package.complete
    if (it->second.sha256 == sha256Hex(readFile(resourcePath(rel), "verify"))) continue;
    out.push_back(it->first + ": not the wording this verifier bundles (written by another "
                  "build of Surrogate, or changed after packing); it is documentation only, "
                  "held by the tag manifests, and no check relies on it");
  }
  return out;
}

void checkRoCrate(const std::filesystem::path& package, const Inventory& inv, const std::string& carrierXml,
                  const Limits& limits, std::vector<Check>& checks) {
  const auto crate = inv.files.find(mapping::kRoCratePath);
  const std::string* info = contentOf(inv, "bag-info.txt");
  if (crate == inv.files.end() || !info) return;  // package.complete
  const BagInfo bagInfo = parseBagInfo(*info);
  auto one = [&](const char* label) { return firstValue(bagInfo, label); };
  mapping::CrateFacts facts;
  facts.packageId = one("Surrogate-Package-Identifier");
  facts.packagingTime = one("Surrogate-Packaging-Time");
  facts.hasReport = inv.files.count(std::string("data/") + capture::kReportPath) > 0;
  std::vector<std::string> problems;
  try {
    const std::string derived = mapping::deriveRoCrate(carrierXml, facts, kCarrierPath);
    const auto same = [&](const std::string& text) {
      return crate->second.size == text.size() && crate->second.sha256 == sha256Hex(text);
    };
    // A package packed before the mappings' current edition holds that edition's crate.
    mapping::CrateFacts earlier = facts;
    earlier.mappingEdition = 1;
    if (!same(derived) && !same(mapping::deriveRoCrate(carrierXml, earlier, kCarrierPath)))
      problems.push_back(std::string(mapping::kRoCratePath) + ": " +
                         firstDifference(derived, readBagFile(package, inv, mapping::kRoCratePath, limits)));
  } catch (const Error& e) {
    if (e.kind() == ErrorKind::Internal || e.kind() == ErrorKind::Fixity) throw;
    problems.push_back(e.text());
  }
  checks.push_back(makeCheck("metadata.ro-crate", Severity::Invalid,
                             "data/ro-crate-metadata.json equals what the bundled stylesheet "
                             "derives from the carrier",
                             "the RO-Crate metadata differ from what the carrier gives", problems));
}

}  // namespace surrogate::verify
