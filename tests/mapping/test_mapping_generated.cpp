// Issue 14 on generated captures: `surrogate run` then `surrogate pack`, and the package's
// metadata/mets.xml and metadata/crm.rdf read as a repository's ingest would read them.
#include <catch2/catch.hpp>

#include <algorithm>
#include <fstream>
#include <set>
#include <sstream>

#include "archival_checks.h"
#include "carrier/carrier.h"
#include "core/digest.h"
#include "e2e_support.h"
#include "formats/pronom.h"
#include "mapping/mapping.h"
#include "pronom_reference.h"

namespace fs = std::filesystem;
using namespace surrogate;

namespace {

int count(const std::string& text, const std::string& what) {
  int n = 0;
  for (std::size_t at = text.find(what); at != std::string::npos; at = text.find(what, at + 1)) ++n;
  return n;
}

struct Packed {
  fs::path capture, package;
  carrier::Carrier carrier;
  std::string mets, crm;
};

// One generated capture, run with rights, licence and Dublin Core metadata, and packed; made
// once per test process.
const Packed& packed() {
  static Packed p = [] {
    Packed r;
    const fs::path dir = e2e::freshDir("archival");
    r.capture = e2e::smallCapture(dir, 8);
    const auto run = e2e::surrogate(
        "run " + e2e::quote(r.capture) +
        " --title \"Stela 12\" --creator \"Ana Silva:photographer\" --operator \"Bo Chen\""
        " --rights \"Images: Museum of Stelae; research use only\""
        " --license https://creativecommons.org/licenses/by-nc/4.0/"
        " --meta Subject=\"funerary stela\" --meta Description=\"limestone, 3rd c. BC\" --quiet");
    if (run.exitCode != 0) throw std::runtime_error("surrogate run failed: " + run.output);
    r.package = dir / "stela12";
    const auto pack = e2e::surrogate("pack " + e2e::quote(r.capture) + " -o " + e2e::quote(r.package) + " --quiet");
    if (pack.exitCode != 0) throw std::runtime_error("surrogate pack failed: " + pack.output);
    r.carrier = carrier::loadCarrier(r.capture / "assembly-files/carrier.xml");
    r.mets = e2e::bytesOf(r.package / "metadata/mets.xml");
    r.crm = e2e::bytesOf(r.package / "metadata/crm.rdf");
    return r;
  }();
  return p;
}

// A library's PREMIS agent identifier: "name version", the version alone when it begins with
// the name (OpenSSL's does).
std::string agentId(const carrier::Software& s) {
  return s.version.rfind(s.name + " ", 0) == 0 ? s.version : s.name + " " + s.version;
}

// The payload paths of the files a pipeline step wrote.
std::vector<std::string> derivedPaths(const carrier::Carrier& c) {
  std::vector<std::string> out;
  for (const carrier::FileRecord& f : c.files)
    if (!f.createdBy.empty()) out.push_back("data/" + f.path);
  return out;
}

// The digiprovMD of one event.
std::string eventText(const std::string& mets, const std::string& id) {
  const auto from = mets.find("<mets:digiprovMD ID=\"" + id + "\">");
  if (from == std::string::npos) return "";
  return mets.substr(from, mets.find("</mets:digiprovMD>", from) - from);
}

// The techMD of the PREMIS object of a payload path.
std::string objectText(const std::string& mets, const std::string& path) {
  const auto at = mets.find("<premis:objectIdentifierValue>" + path + "</premis:objectIdentifierValue>");
  if (at == std::string::npos) return "";
  const auto from = mets.rfind("<mets:techMD ", at);
  return mets.substr(from, mets.find("</mets:techMD>", at) - from);
}

}  // namespace

TEST_CASE("generated capture: METS validates, every PREMIS link resolves, each agent once, a MIMETYPE on every file", "[mapping][generated][premis]") {
  const Packed& p = packed();
  CHECK_NOTHROW(mapping::validateMets(p.mets, "metadata/mets.xml"));
  const archival::Premis premis = archival::readPremis(p.mets);
  for (const std::string& problem : archival::linkProblems(premis)) FAIL_CHECK(problem);
  REQUIRE_FALSE(premis.files.empty());
  for (const auto& [href, mime] : premis.files) {
    INFO(href);
    CHECK_FALSE(mime.empty());
  }
  CHECK(p.mets.find("MIMETYPE=\"application/xml\"") != std::string::npos);  // carrier.xml
  CHECK(p.mets.find("MIMETYPE=\"text/html\"") != std::string::npos);       // report.html
  // One intellectual entity for the capture; every file is included in it.
  CHECK(count(p.mets, "xsi:type=\"premis:intellectualEntity\"") == 1);
  CHECK(count(p.mets, "<premis:relationshipSubType>is included in</premis:relationshipSubType>") ==
        static_cast<int>(premis.files.size()));
  // Each library the header records is one agent, linked to the steps that used it.
  for (const carrier::Software& s : p.carrier.header.software) {
    INFO(s.name);
    CHECK(count(p.mets, "<premis:agentIdentifierValue>" + agentId(s) + "</premis:agentIdentifierValue>") == 1);
  }
}

TEST_CASE("generated capture: every step is a typed, dated event with its operator, Surrogate and its libraries", "[mapping][generated][premis]") {
  const Packed& p = packed();
  const auto version = [&](const std::string& name) {
    for (const carrier::Software& s : p.carrier.header.software)
      if (s.name == name) return agentId(s);
    return std::string("?");
  };
  for (const carrier::Step& s : p.carrier.process) {
    const std::string event = eventText(p.mets, "event-" + s.id);
    INFO(s.id << " " << s.component);
    REQUIRE_FALSE(event.empty());
    CHECK(event.find("valueURI=\"http://id.loc.gov/vocabulary/preservation/eventType/") != std::string::npos);
    CHECK(event.find("<premis:eventOutcome>success</premis:eventOutcome>") != std::string::npos);
    CHECK(event.find("Z</premis:eventDateTime>") != std::string::npos);  // with its zone (UTC)
    CHECK(event.find("<premis:linkingAgentIdentifierValue>Bo Chen</premis:linkingAgentIdentifierValue>") != std::string::npos);
    CHECK(event.find("<premis:linkingAgentIdentifierValue>" + version("Surrogate") + "</premis:linkingAgentIdentifierValue>") != std::string::npos);
    CHECK(event.find("<premis:linkingObjectRole>source</premis:linkingObjectRole>") != std::string::npos);
  }
  const auto eventOf = [&](const std::string& component) {
    for (const carrier::Step& s : p.carrier.process)
      if (s.component == component) return eventText(p.mets, "event-" + s.id);
    return std::string();
  };
  CHECK(eventOf("ImageDecode").find(version("LibRaw")) != std::string::npos);
  CHECK(eventOf("ImageDecode").find(">interpreting</premis:eventType>") != std::string::npos);
  CHECK(eventOf("CaptureIngest").find(version("Exiv2")) != std::string::npos);
  CHECK(eventOf("SphereDetection").find(version("OpenCV")) != std::string::npos);
  CHECK(eventOf("RtiFit").find(version("Eigen")) != std::string::npos);
  CHECK(eventOf("RtiFit").find(version("LibRaw")) == std::string::npos);
  CHECK(eventOf("RtiFit").find(">creation</premis:eventType>") != std::string::npos);
  // The fit used the light directions of lights.lp and the images.
  CHECK(eventOf("RtiFit").find("data/assembly-files/lights.lp</premis:linkingObjectIdentifierValue>") != std::string::npos);
  CHECK(eventOf("DerivedMaps").find("data/finished-files/ptm-lrgb.ptm</premis:linkingObjectIdentifierValue>") != std::string::npos);
  // The command run that wrote the record links libxml2, which wrote and checked it.
  CHECK(eventText(p.mets, "event-run-r1").find(version("libxml2")) != std::string::npos);
}

TEST_CASE("generated capture: every file a step made has a PREMIS path of derivations and events back to the photographs", "[mapping][generated][premis]") {
  const Packed& p = packed();
  const std::vector<std::string> derived = derivedPaths(p.carrier);
  REQUIRE(derived.size() >= 8);  // overlays, lights.lp, PTM, HSH, maps, previews
  for (const std::string& problem : archival::derivationProblems(archival::readPremis(p.mets), derived))
    FAIL_CHECK(problem);
}

TEST_CASE("generated capture: formats with version and PRONOM identifier where certain, the reason where not", "[mapping][generated][premis][formats]") {
  const Packed& p = packed();
  const std::string normals = objectText(p.mets, "data/finished-files/normals.png");
  CHECK(normals.find("<premis:formatVersion>1.2</premis:formatVersion>") != std::string::npos);
  CHECK(normals.find("<premis:formatRegistryKey>fmt/13</premis:formatRegistryKey>") != std::string::npos);
  CHECK(objectText(p.mets, "data/assembly-files/carrier.xml").find("<premis:formatRegistryKey>fmt/101</premis:formatRegistryKey>") != std::string::npos);
  CHECK(objectText(p.mets, "data/finished-files/report.html").find("<premis:formatRegistryKey>fmt/471</premis:formatRegistryKey>") != std::string::npos);
  const std::string ptm = objectText(p.mets, "data/finished-files/ptm-lrgb.ptm");
  CHECK(ptm.find("<premis:formatVersion>1.2</premis:formatVersion>") != std::string::npos);
  CHECK(ptm.find("<premis:formatRegistryKey>fmt/519</premis:formatRegistryKey>") != std::string::npos);
  CHECK(objectText(p.mets, "data/finished-files/hsh2.rti").find("PRONOM has no entry") != std::string::npos);
  CHECK(objectText(p.mets, "data/assembly-files/lights.lp").find("PRONOM has no entry") != std::string::npos);
  const std::string dng = objectText(p.mets, "data/original-captures/IMG_0001.dng");
  CHECK(dng.find("<premis:formatName>Digital Negative Format (DNG)</premis:formatName>") != std::string::npos);
  CHECK(dng.find("<premis:formatRegistryKey>fmt/730</premis:formatRegistryKey>") != std::string::npos);
  CHECK(objectText(p.mets, "data/jpeg-exports/IMG_0001.jpg").find("<premis:formatRegistryKey>fmt/43</premis:formatRegistryKey>") != std::string::npos);
  // Both fixities and the size on every file object.
  CHECK(count(p.mets, "<premis:messageDigestAlgorithm>SHA-512</premis:messageDigestAlgorithm>") ==
        count(p.mets, "<premis:messageDigestAlgorithm>SHA-256</premis:messageDigestAlgorithm>"));
}

// Issue 42: every payload file's PRONOM identifier in mets.xml is the one PRONOM's published
// signatures give its bytes (tests/formats/pronom_reference.h, release 118), and is absent where
// they give none.
TEST_CASE("generated capture: every PRONOM identifier in mets.xml is the one PRONOM's signatures give the file", "[mapping][generated][premis][formats][pronom]") {
  const Packed& p = packed();
  std::vector<std::string> paths = {"assembly-files/carrier.xml", "finished-files/report.html", "ro-crate-metadata.json"};
  for (const carrier::FileRecord& f : p.carrier.files) paths.push_back(f.path);
  std::set<std::string> seen;
  for (const std::string& path : paths) {
    INFO(path);
    const std::string object = objectText(p.mets, "data/" + path);
    REQUIRE_FALSE(object.empty());
    const std::string bytes = e2e::bytesOf(p.package / "data" / path);
    // As Siegfried and fido: the signatures, then text by its name (formats/pronom.h, issue 56).
    const formats::PronomIdentity id = formats::identifyPronomNamed(bytes, fs::path(path).filename().string());
    if (!id.identified()) {
      CHECK(object.find("<premis:formatRegistryKey>") == std::string::npos);
      continue;
    }
    CHECK(object.find("<premis:formatRegistryKey>" + id.puid + "</premis:formatRegistryKey>") != std::string::npos);
    seen.insert(id.puid);
    const auto kept = pronom_reference::puids();
    if (std::find(kept.begin(), kept.end(), id.puid) == kept.end()) continue;
    CHECK(pronom_reference::matches(id.puid, bytes));
    for (const std::string& preferred : pronom_reference::preferredTo(id.puid)) CHECK_FALSE(pronom_reference::matches(preferred, bytes));
  }
  // DNG 1.4 originals, JFIF 1.01 exports, PNG 1.2 pictures, a PTM, the HTML 5 report, the
  // carrier (XML 1.0), the .lp (plain text) and the RO-Crate's metadata (JSON).
  CHECK(seen == std::set<std::string>{"fmt/730", "fmt/43", "fmt/13", "fmt/519", "fmt/471", "fmt/101", "x-fmt/111", "fmt/817"});
}

TEST_CASE("generated capture: JPEG exports are flagged as processed outside Surrogate, the capture date says it has no zone", "[mapping][generated][premis]") {
  const Packed& p = packed();
  const std::string jpeg = objectText(p.mets, "data/jpeg-exports/IMG_0001.jpg");
  CHECK(jpeg.find("processed outside Surrogate: made by other software from data/original-captures/IMG_0001.dng") != std::string::npos);
  CHECK(jpeg.find("<premis:relationshipType>derivation</premis:relationshipType>") != std::string::npos);
  const std::string capture = eventText(p.mets, "event-capture");
  CHECK(capture.find(">capture</premis:eventType>") != std::string::npos);
  CHECK(capture.find("local time of the camera, time zone not recorded") != std::string::npos);
}

TEST_CASE("generated capture: rights, licence and Dublin Core from the command line reach the carrier and the METS", "[mapping][generated][rights]") {
  const Packed& p = packed();
  CHECK(p.carrier.header.rights == "Images: Museum of Stelae; research use only");
  CHECK(p.carrier.header.license == "https://creativecommons.org/licenses/by-nc/4.0/");
  CHECK(p.mets.find("<premis:rightsBasis>license</premis:rightsBasis>") != std::string::npos);
  CHECK(p.mets.find("<premis:otherRightsNote>Images: Museum of Stelae; research use only</premis:otherRightsNote>") != std::string::npos);
  for (const std::string dc : {"<dc:title>Stela 12</dc:title>", "<dc:creator>Ana Silva</dc:creator>",
                               "<dc:subject>funerary stela</dc:subject>", "<dc:description>limestone, 3rd c. BC</dc:description>",
                               "<dc:rights>https://creativecommons.org/licenses/by-nc/4.0/</dc:rights>", "<dc:date>"}) {
    INFO(dc);
    CHECK(p.mets.find(dc) != std::string::npos);
  }
}

TEST_CASE("generated capture: rights and licence stand as decisions across runs and a change is recorded", "[mapping][generated][rights]") {
  const fs::path dir = e2e::freshDir("rights-runs");
  const fs::path capture = e2e::smallCapture(dir, 8);
  REQUIRE(e2e::surrogate("run " + e2e::quote(capture) + " --rights \"research only\" --license https://example.org/l1 --quiet").exitCode == 0);
  REQUIRE(e2e::surrogate("run " + e2e::quote(capture) + " --quiet").exitCode == 0);
  carrier::Carrier c = carrier::loadCarrier(capture / "assembly-files/carrier.xml");
  CHECK(c.header.rights == "research only");
  CHECK(c.header.license == "https://example.org/l1");
  REQUIRE(e2e::surrogate("run " + e2e::quote(capture) + " --rights \"open access\" --quiet").exitCode == 0);
  c = carrier::loadCarrier(capture / "assembly-files/carrier.xml");
  CHECK(c.header.rights == "open access");
  CHECK(c.header.license == "https://example.org/l1");
  REQUIRE(c.header.runs.size() == 3);
  CHECK(c.header.runs.back().notes.at(0) == "rights \"research only\" -> \"open access\"");
  // A licence that is not a URI is refused before any work.
  const auto bad = e2e::surrogate("run " + e2e::quote(capture) + " --license \"CC BY 4.0\" --quiet");
  CHECK(bad.exitCode == 2);  // a usage error
  CHECK(bad.output.find("--license") != std::string::npos);
}

TEST_CASE("generated capture: crm.rdf keeps every domain and range, nests its time-spans and chains each result to the photographs", "[mapping][generated][crm]") {
  const Packed& p = packed();
  const std::vector<archival::Triple> triples = archival::rdfTriples(p.crm, p.package.parent_path().string());
  REQUIRE(triples.size() > 300);
  for (const std::string& problem :
       archival::crmTermProblems(triples, std::string(SURROGATE_SOURCE_DIR) + "/tests/mapping/data/crm-terms.tsv"))
    FAIL_CHECK(problem);
  for (const std::string& problem : archival::timeSpanNestingProblems(triples)) FAIL_CHECK(problem);
  for (const std::string& problem : archival::crmDerivationProblems(triples)) FAIL_CHECK(problem);
  // Every step that ran had inputs.
  std::set<std::string> withInput;
  for (const auto& t : triples)
    if (t.p == "http://www.cidoc-crm.org/extensions/crmdig/L10_had_input") withInput.insert(t.s);
  for (const carrier::Step& s : p.carrier.process) {
    INFO(s.id);
    bool found = false;
    for (const std::string& n : withInput) found = found || n.size() > s.id.size() && n.compare(n.size() - s.id.size() - 5, std::string::npos, "step/" + s.id) == 0;
    CHECK(found);
  }
  CHECK(p.crm.find("CIDOC-CRM 7.1.3") != std::string::npos);
}

TEST_CASE("generated capture: the package with the new metadata verifies", "[mapping][generated]") {
  const Packed& p = packed();
  const auto verify = e2e::surrogate("verify " + e2e::quote(p.package) + " --quiet");
  INFO(verify.output);
  CHECK(verify.exitCode == 0);
}

namespace {

// A bag-info.txt field of a package (its first value), or "".
std::string bagInfo(const fs::path& package, const std::string& label) {
  std::istringstream in(e2e::bytesOf(package / "bag-info.txt"));
  for (std::string line; std::getline(in, line);)
    if (line.rfind(label + ": ", 0) == 0) return line.substr(label.size() + 2);
  return "";
}

// The tag manifests redone for the tag files as they now are, as RFC 8493 asks of whoever edits
// a tag file (docs/package.md, "Fields a holder adds").
void redoTagManifests(const fs::path& package) {
  for (const std::string algorithm : {"sha256", "sha512"}) {
    const fs::path manifest = package / ("tagmanifest-" + algorithm + ".txt");
    std::istringstream in(e2e::bytesOf(manifest));
    std::string out;
    for (std::string line; std::getline(in, line);) {
      const std::string path = line.substr(line.find("  ") + 2);
      const auto d = digestFile(package / path, true);
      out += (algorithm == "sha256" ? d.sha256 : d.sha512) + "  " + path + "\n";
    }
    std::ofstream(manifest, std::ios::binary) << out;
  }
}

// The objects of the triples with subject `s` and predicate `p`.
std::set<std::string> objectsOf(const std::vector<archival::Triple>& triples, const std::string& s, const std::string& p) {
  std::set<std::string> out;
  for (const auto& t : triples)
    if (t.s == s && t.p == p) out.insert(t.o);
  return out;
}

const std::string kCrm = "http://www.cidoc-crm.org/cidoc-crm/";

// The symbolic content of every identifier (P1 -> E42 -> P190) of node `s`.
std::set<std::string> identifiersOf(const std::vector<archival::Triple>& triples, const std::string& s) {
  std::set<std::string> out;
  for (const std::string& id : objectsOf(triples, s, kCrm + "P1_is_identified_by"))
    for (const std::string& value : objectsOf(triples, id, kCrm + "P190_has_symbolic_content"))
      out.insert(value.substr(1, value.rfind('"') - 1));
  return out;
}

}  // namespace

TEST_CASE("generated capture: the package and capture identifiers are the same strings in bag-info, METS and CRM", "[mapping][generated][identifiers]") {
  const Packed& p = packed();
  const std::string packageId = bagInfo(p.package, "Surrogate-Package-Identifier");
  const std::string captureId = bagInfo(p.package, "Surrogate-Capture-Identifier");
  // Both from their published definitions: the SHA-256 of the carrier's bytes, and of the first
  // photograph's (the carrier's first file), computed here.
  CHECK(packageId == "urn:sha256:" + digestFile(p.capture / "assembly-files/carrier.xml").sha256);
  REQUIRE(p.carrier.files.front().role == "original");
  CHECK(captureId == "urn:surrogate:capture:" + digestFile(p.capture / p.carrier.files.front().path).sha256);
  CHECK(bagInfo(p.package, "Surrogate-Previous-Package-Identifier").empty());  // its first package

  CHECK(p.mets.find("OBJID=\"" + packageId + "\"") != std::string::npos);
  CHECK(p.mets.find("<mets:altRecordID TYPE=\"Surrogate capture identifier\">" + captureId + "</mets:altRecordID>") != std::string::npos);
  const archival::Premis premis = archival::readPremis(p.mets);
  std::set<std::pair<std::string, std::string>> entity;
  for (const auto& o : premis.objects)
    if (o.kind == "premis:intellectualEntity") entity.insert(o.ids.begin(), o.ids.end());
  CHECK(entity.count({"Surrogate package identifier", packageId}) == 1);
  CHECK(entity.count({"Surrogate capture identifier", captureId}) == 1);

  const std::vector<archival::Triple> triples = archival::rdfTriples(p.crm, p.package.parent_path().string());
  // The package is the node named by its identifier, a CRMdig digital object identified by it,
  // about the digitization, which the capture identifier identifies.
  CHECK(objectsOf(triples, packageId, "http://www.w3.org/1999/02/22-rdf-syntax-ns#type").count(
            "http://www.cidoc-crm.org/extensions/crmdig/D1_Digital_Object") == 1);
  CHECK(identifiersOf(triples, packageId) == std::set<std::string>{packageId});
  const std::set<std::string> about = objectsOf(triples, packageId, kCrm + "P129_is_about");
  REQUIRE(about.size() == 1);
  CHECK(*about.begin() == captureId + "/capture");
  CHECK(identifiersOf(triples, *about.begin()) == std::set<std::string>{captureId});
  CHECK(objectsOf(triples, packageId, kCrm + "P106_is_composed_of").size() == p.carrier.files.size());
  CHECK(objectsOf(triples, packageId, kCrm + "P130_shows_features_of").empty());
}

TEST_CASE("generated capture: a re-pack after the record changed revises the previous package, under a repository's base URI, and verifies", "[mapping][generated][identifiers]") {
  const Packed& p = packed();
  const fs::path dir = e2e::freshDir("repack");
  const fs::path capture = dir / "capture";
  fs::copy(p.capture, capture, fs::copy_options::recursive);  // with its record of packages
  const std::string first = bagInfo(p.package, "Surrogate-Package-Identifier");

  // The same record packed again: the same identifier, still no previous package.
  const fs::path again = dir / "again";
  REQUIRE(e2e::surrogate("pack " + e2e::quote(capture) + " -o " + e2e::quote(again) + " --quiet").exitCode == 0);
  CHECK(bagInfo(again, "Surrogate-Package-Identifier") == first);
  CHECK(bagInfo(again, "Surrogate-Previous-Package-Identifier").empty());

  // A new decision changes the record: the next package revises the first.
  REQUIRE(e2e::surrogate("run " + e2e::quote(capture) + " --meta Coverage=Thebes --quiet").exitCode == 0);
  const fs::path second = dir / "second";
  const std::string base = "https://repository.example/capture/stela12/";
  const auto pack = e2e::surrogate("pack " + e2e::quote(capture) + " -o " + e2e::quote(second) + " --base-uri " + base);
  REQUIRE(pack.exitCode == 0);
  const std::string secondId = bagInfo(second, "Surrogate-Package-Identifier");
  CHECK(secondId != first);
  CHECK(pack.output.find("revises the package " + first) != std::string::npos);
  CHECK(bagInfo(second, "Surrogate-Previous-Package-Identifier") == first);
  CHECK(bagInfo(second, "Surrogate-Base-URI") == base);
  CHECK(bagInfo(second, "Surrogate-Capture-Identifier") == bagInfo(p.package, "Surrogate-Capture-Identifier"));

  // METS: the intellectual entity is derived from ("has source") the previous package.
  const std::string mets = e2e::bytesOf(second / "metadata/mets.xml");
  CHECK_NOTHROW(mapping::validateMets(mets, "metadata/mets.xml"));
  bool revises = false;
  for (const auto& o : archival::readPremis(mets).objects)
    if (o.kind == "premis:intellectualEntity")
      for (const auto& l : o.derivedFrom) revises = revises || (l.type == "Surrogate package identifier" && l.value == first);
  CHECK(revises);

  // CRM: the package shows features of the previous one; every minted node is under the base.
  const std::string crm = e2e::bytesOf(second / "metadata/crm.rdf");
  const std::vector<archival::Triple> triples = archival::rdfTriples(crm, dir.string());
  CHECK(objectsOf(triples, secondId, kCrm + "P130_shows_features_of") == std::set<std::string>{first});
  int minted = 0;
  for (const auto& t : triples) {
    // the packages, named by their identifiers; the licence, by its own URI
    if (t.s == secondId || t.s == first || t.s == p.carrier.header.license) continue;
    INFO(t.s);
    CHECK(t.s.rfind(base, 0) == 0);
    ++minted;
  }
  CHECK(minted > 300);
  CHECK(crm.find("urn:surrogate:capture:") != std::string::npos);  // the capture identifier, as its E42's value
  for (const std::string& problem :
       archival::crmTermProblems(triples, std::string(SURROGATE_SOURCE_DIR) + "/tests/mapping/data/crm-terms.tsv"))
    FAIL_CHECK(problem);

  const auto verify = e2e::surrogate("verify " + e2e::quote(second) + " --quiet");
  INFO(verify.output);
  CHECK(verify.exitCode == 0);
}

TEST_CASE("generated capture: an identifier forged in bag-info is found by verify, the tag manifests redone", "[mapping][generated][identifiers]") {
  const Packed& p = packed();
  const fs::path dir = e2e::freshDir("forged-ids");
  const std::string captureId = bagInfo(p.package, "Surrogate-Capture-Identifier");
  const std::string packageId = bagInfo(p.package, "Surrogate-Package-Identifier");
  const std::string other = "urn:sha256:" + std::string(64, 'a');
  struct Forgery {
    std::string name, from, to, finding;
  };
  for (const Forgery& f : std::vector<Forgery>{
           {"capture", "Surrogate-Capture-Identifier: " + captureId, "Surrogate-Capture-Identifier: urn:surrogate:capture:" + std::string(64, 'b'),
            "Surrogate-Capture-Identifier is"},
           // a previous package the packer did not name: crm.rdf and mets.xml do not say it
           {"previous", "Surrogate-Package-Identifier: " + packageId,
            "Surrogate-Package-Identifier: " + packageId + "\nSurrogate-Previous-Package-Identifier: " + other, "metadata.derived"},
           {"previous-self", "Surrogate-Package-Identifier: " + packageId,
            "Surrogate-Package-Identifier: " + packageId + "\nSurrogate-Previous-Package-Identifier: " + packageId,
            "is this package's own identifier"},
           {"base", "Surrogate-Package-Identifier: " + packageId,
            "Surrogate-Package-Identifier: " + packageId + "\nSurrogate-Base-URI: https://elsewhere.example/", "metadata.derived"}}) {
    INFO(f.name);
    const fs::path bag = dir / f.name;
    fs::copy(p.package, bag, fs::copy_options::recursive);
    std::string info = e2e::bytesOf(bag / "bag-info.txt");
    const auto at = info.find(f.from);
    REQUIRE(at != std::string::npos);
    info.replace(at, f.from.size(), f.to);
    std::ofstream(bag / "bag-info.txt", std::ios::binary) << info;
    redoTagManifests(bag);
    const auto verify = e2e::surrogate("verify " + e2e::quote(bag));
    INFO(verify.output);
    CHECK(verify.exitCode == 2);
    CHECK(verify.output.find(f.finding) != std::string::npos);
  }
}
