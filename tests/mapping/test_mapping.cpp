// The stylesheets: METS+PREMIS valid against the vendored schemas offline, CIDOC-CRM parsed by
// rapper with the key classes and properties, deterministic output, safe processing.
#include <catch2/catch.hpp>

#include <libxslt/xsltconfig.h>
#include <unistd.h>

#include <algorithm>
#include <array>
#include <atomic>
#include <cstdio>
#include <fstream>
#include <regex>
#include <set>

#include "carrier/carrier.h"
#include "core/digest.h"
#include "core/resources.h"
#include "core/error.h"
#include "mapping/mapping.h"
#include "archival_checks.h"
#include "sample_capture.h"
#include "sample_facts.h"
#include "test_files.h"

namespace fs = std::filesystem;
using namespace surrogate;
using testfiles::freshDir;
using testfiles::slurp;

namespace {
std::string run(const std::string& command) {
  std::string out;
  FILE* pipe = ::popen((command + " 2>&1").c_str(), "r");
  std::array<char, 4096> buffer{};
  while (pipe && std::fgets(buffer.data(), buffer.size(), pipe)) out += buffer.data();
  if (pipe) ::pclose(pipe);
  return out;
}

struct Sample {
  fs::path capture;
  std::string carrierXml;
  mapping::PackageFacts facts;
};

Sample sampleOf(const fs::path& capture) {
  Sample s;
  s.capture = capture;
  s.carrierXml = slurp(s.capture / "assembly-files/carrier.xml");
  s.facts = samplefacts::of(s.capture, s.carrierXml);
  return s;
}

Sample sample(const std::string& name) { return sampleOf(samplecapture::make(freshDir(name))); }

// The sample capture with a history: three command runs in the header (two completed, the last
// failed), an "other" file the capture brings, and an accept-changed-original intervention on
// the ingest step. The carrier text is patched (the carrier API is not needed for this) and
// written back, so that the payload digests are those of the patched carrier.
const char* const kAcceptedHash = "sha256:4a5e1e4baab89f3a32518a88c31bc87f618f76673e2cc77ab2127b7afdeda33b";

Sample sampleWithHistory(const std::string& name) {
  const fs::path capture = samplecapture::make(freshDir(name));
  const std::string notes = "Shot in gallery 3; the dome was not used.\n";
  fs::create_directories(capture / "notes");
  std::ofstream(capture / "notes/session notes.txt", std::ios::binary) << notes;
  std::string xml = slurp(capture / "assembly-files/carrier.xml");
  const auto insertBefore = [&xml](const std::string& at, const std::string& text) {
    const auto where = xml.find(at);
    REQUIRE(where != std::string::npos);
    xml.insert(where, text);
  };
  insertBefore("  </header>",
               "    <run id=\"r1\" command=\"run\" who=\"Eli Park\" started=\"2026-01-02T09:00:00Z\" "
               "ended=\"2026-01-02T09:00:04Z\" outcome=\"completed\"><arg>--quiet</arg></run>\n"
               "    <run id=\"r2\" command=\"run\" who=\"Dee Ortiz\" started=\"2026-01-02T10:00:00Z\" "
               "ended=\"2026-01-02T10:00:05Z\" outcome=\"completed\"><arg>--exclude</arg><arg>IMG_0003</arg>"
               "<arg>--reason</arg><arg>the flash did not fire</arg><arg>--accept-changed</arg>"
               "<arg>original-captures/IMG_0002.dng</arg><arg>--reason</arg><arg>re-exported by the museum</arg>"
               "<note>exclude-image original-captures/IMG_0003.dng: the flash did not fire</note>"
               "<note>accepted the change of original-captures/IMG_0002.dng (now " +
                   std::string(kAcceptedHash) + "): re-exported by the museum</note></run>\n"
               "    <run id=\"r3\" command=\"lights\" who=\"Ana Silva\" started=\"2026-01-03T08:00:00Z\" "
               "ended=\"2026-01-03T08:00:01Z\" outcome=\"failed\"><arg>--sphere</arg><arg>339,57,45</arg>"
               "<arg>--reason</arg><arg>cut by frame</arg><arg></arg>"
               "<note>manual-sphere 0 = 339,57,45: cut by frame</note>"
               "<note>failed: sphere 0 lies outside the frame</note></run>\n");
  insertBefore("  </files>",
               "    <file id=\"f11\" path=\"notes/session notes.txt\" role=\"other\" size=\"" +
                   std::to_string(notes.size()) + "\" sha256=\"" + sha256Hex(notes) +
                   "\" format=\"TXT\" mediaType=\"text/plain\"/>\n");
  insertBefore("    </step>",
               "      <intervention kind=\"accept-changed-original\" target=\"original-captures/IMG_0002.dng\" "
               "value=\"" + std::string(kAcceptedHash) + "\" who=\"Dee Ortiz\" time=\"2026-01-02T10:00:00Z\">"
               "re-exported by the museum</intervention>\n");
  std::ofstream(capture / "assembly-files/carrier.xml", std::ios::binary) << xml;
  return sampleOf(capture);
}

int count(const std::string& text, const std::string& what) {
  int n = 0;
  for (std::size_t at = text.find(what); at != std::string::npos; at = text.find(what, at + 1)) ++n;
  return n;
}
}  // namespace

TEST_CASE("METS with PREMIS derived from a carrier validates against the vendored schemas", "[mapping][mets]") {
  const Sample s = sample("mets");
  const std::string mets = mapping::deriveMets(s.carrierXml, s.facts);
  CHECK_NOTHROW(mapping::validateMets(mets, "mets.xml"));

  // Every payload file is in the fileSec, with its SHA-256, and has a PREMIS object with both
  // fixities, its size and (where known) its PRONOM id.
  CHECK(count(mets, "<mets:file ") == static_cast<int>(s.facts.payload.size()));
  // ... and the capture itself is one more object: the intellectual entity.
  CHECK(count(mets, "<premis:object ") == static_cast<int>(s.facts.payload.size()) + 1);
  CHECK(count(mets, "<premis:object xsi:type=\"premis:intellectualEntity\"") == 1);
  for (const mapping::PayloadFile& f : s.facts.payload) {
    INFO(f.path);
    CHECK(mets.find("xlink:href=\"" + f.path + "\"") != std::string::npos);
    CHECK(mets.find("CHECKSUM=\"" + f.sha256 + "\"") != std::string::npos);
    CHECK(mets.find("<premis:messageDigest>" + f.sha512 + "</premis:messageDigest>") != std::string::npos);
  }
  CHECK(mets.find("<premis:formatRegistryKey>fmt/43</premis:formatRegistryKey>") != std::string::npos);
  CHECK(mets.find("<premis:creatingApplicationName>Canon EOS 5D Mark IV</premis:creatingApplicationName>") != std::string::npos);
  CHECK(mets.find("<premis:creatingApplicationName>Surrogate RtiFit</premis:creatingApplicationName>") != std::string::npos);
  // Events: capture, each step, message digest calculation, packaging; with outcomes and agents.
  CHECK(mets.find("eventType/cap\">capture</premis:eventType>") != std::string::npos);
  CHECK(mets.find("eventType/mes\">message digest calculation</premis:eventType>") != std::string::npos);
  CHECK(mets.find("eventType/ipc\">information package creation</premis:eventType>") != std::string::npos);
  CHECK(mets.find("event-s1") != std::string::npos);
  CHECK(mets.find("event-s2") != std::string::npos);
  CHECK(count(mets, "<premis:eventOutcome>success</premis:eventOutcome>") == 5);
  CHECK(mets.find("<premis:eventDateTime>2026-01-01T12:00:01</premis:eventDateTime>") != std::string::npos);
  CHECK(mets.find("intervention exclude-image on original-captures/IMG_0003.dng by Bo Chen") != std::string::npos);
  CHECK(mets.find("<premis:agentName>Ana Silva</premis:agentName>") != std::string::npos);
  CHECK(mets.find("<premis:agentName>Bo Chen</premis:agentName>") != std::string::npos);
  CHECK(mets.find("<premis:agentType>hardware</premis:agentType>") != std::string::npos);
  CHECK(mets.find("<premis:agentVersion>") != std::string::npos);
  CHECK(mets.find("OBJID=\"" + s.facts.packageId + "\"") != std::string::npos);
  CHECK(mets.find("<mets:altRecordID TYPE=\"External-Identifier\">INV-42</mets:altRecordID>") != std::string::npos);
}

TEST_CASE("invalid PREMIS inside METS is caught by validation", "[mapping][mets]") {
  const Sample s = sample("bad-premis");
  std::string mets = mapping::deriveMets(s.carrierXml, s.facts);
  const auto at = mets.find("<premis:size>");
  REQUIRE(at != std::string::npos);
  mets.insert(at, "<premis:bogus/>");
  try {
    mapping::validateMets(mets, "broken-mets.xml");
    FAIL("no error");
  } catch (const Error& e) {
    CHECK(e.file() == "broken-mets.xml");
    CHECK(e.message().find("bogus") != std::string::npos);
  }
  std::string noFileSecId = mapping::deriveMets(s.carrierXml, s.facts);
  // A METS file ID that is not an xs:ID (it begins with a digit).
  const auto id = noFileSecId.find("<mets:file ID=\"") + 15;
  noFileSecId.replace(id, noFileSecId.find('"', id) - id, "1-bad");
  CHECK_THROWS_AS(mapping::validateMets(noFileSecId, "mets.xml"), Error);
}

TEST_CASE("validation works offline: schemas are never fetched", "[mapping][mets]") {
  // With no network namespace tricks available, make any network attempt impossible to
  // succeed: an unroutable proxy. Validation must still pass, from the local copies.
  ::setenv("http_proxy", "http://127.0.0.1:9", 1);
  ::setenv("HTTP_PROXY", "http://127.0.0.1:9", 1);
  const Sample s = sample("offline");
  CHECK_NOTHROW(mapping::validateMets(mapping::deriveMets(s.carrierXml, s.facts), "mets.xml"));
  ::unsetenv("http_proxy");
  ::unsetenv("HTTP_PROXY");
}

TEST_CASE("CIDOC-CRM derived from a carrier parses with rapper and has the key classes", "[mapping][crm]") {
  const Sample s = sample("crm");
  const std::string crm = mapping::deriveCrm(s.carrierXml);
  CHECK_NOTHROW(mapping::checkRdfWellFormed(crm, "crm.rdf"));
  const fs::path file = s.capture.parent_path() / "crm.rdf";
  std::ofstream(file, std::ios::binary) << crm;

  const std::string parsed = run("rapper -q -i rdfxml -o ntriples " + file.string());
  std::smatch m;
  const std::string counted = run("rapper -i rdfxml -c " + file.string());
  REQUIRE(std::regex_search(counted, m, std::regex("returned ([0-9]+) triples")));
  const int triples = std::stoi(m[1]);
  CHECK(triples > 150);
  CHECK(count(parsed, "\n") == triples);

  const std::string crmNs = "http://www.cidoc-crm.org/cidoc-crm/";
  const std::string dig = "http://www.cidoc-crm.org/extensions/crmdig/";
  const std::string type = "<http://www.w3.org/1999/02/22-rdf-syntax-ns#type> ";
  for (const std::string& cls : {dig + "D2_Digitization_Process", dig + "D8_Digital_Device", dig + "D9_Data_Object",
                                 dig + "D10_Software_Execution", dig + "D14_Software", dig + "D1_Digital_Object",
                                 crmNs + "E22_Human-Made_Object", crmNs + "E21_Person", crmNs + "E52_Time-Span",
                                 crmNs + "E7_Activity"}) {
    INFO(cls);
    CHECK(parsed.find(type + "<" + cls + ">") != std::string::npos);
  }
  for (const std::string& p : {dig + "L1_digitized", dig + "L12_happened_on_device", dig + "L23_used_software_or_firmware",
                               dig + "L10_had_input", dig + "L11_had_output", dig + "L13_used_parameters",
                               crmNs + "P14_carried_out_by", crmNs + "P4_has_time-span", crmNs + "P82a_begin_of_the_begin",
                               crmNs + "P1_is_identified_by", crmNs + "P190_has_symbolic_content", crmNs + "P134_continued"}) {
    INFO(p);
    CHECK(parsed.find("<" + p + ">") != std::string::npos);
  }
  // The camera's make, model and serial; a file's hash; a step's software version.
  CHECK(parsed.find("\"0123456789\"") != std::string::npos);
  CHECK(parsed.find("\"Canon EOS 5D Mark IV\"") != std::string::npos);
  CHECK(parsed.find("\"" + digestFile(s.capture / "original-captures/IMG_0001.dng").sha256 + "\"") != std::string::npos);
  CHECK(parsed.find("\"version 2\"") != std::string::npos);
  CHECK(parsed.find("\"basis=ptm-lrgb\"") != std::string::npos);
  CHECK(parsed.find("\"reason: the flash did not fire\"") != std::string::npos);
  CHECK(parsed.find("\"2026-01-01T12:00:01\"^^<http://www.w3.org/2001/XMLSchema#dateTime>") != std::string::npos);
}

TEST_CASE("the same carrier gives the same bytes", "[mapping]") {
  const Sample s = sample("determinism");
  CHECK(mapping::deriveCrm(s.carrierXml) == mapping::deriveCrm(s.carrierXml));
  CHECK(mapping::deriveMets(s.carrierXml, s.facts) == mapping::deriveMets(s.carrierXml, s.facts));
}

TEST_CASE("a carrier with a DOCTYPE or external entity is refused, nothing is read", "[mapping][safety]") {
  const std::string xxe =
      "<?xml version=\"1.0\"?><!DOCTYPE c [<!ENTITY x SYSTEM \"file:///etc/passwd\">]>"
      "<carrier xmlns=\"urn:surrogate:carrier:1\" version=\"1.0\"><header><title>&x;</title></header></carrier>";
  try {
    mapping::deriveCrm(xxe, "evil.xml");
    FAIL("no error");
  } catch (const Error& e) {
    CHECK(e.file() == "evil.xml");
    CHECK(e.message().find("DOCTYPE") != std::string::npos);
  }
  CHECK_THROWS_AS(mapping::deriveCrm("<carrier", "broken.xml"), Error);
}

TEST_CASE("without a payload list, METS lists the carrier's own files", "[mapping][mets]") {
  const Sample s = sample("nofiles");
  mapping::PackageFacts facts = s.facts;
  facts.payload.clear();
  const std::string mets = mapping::deriveMets(s.carrierXml, facts);
  CHECK_NOTHROW(mapping::validateMets(mets, "mets.xml"));
  CHECK(mets.find("data/assembly-files/carrier.xml") == std::string::npos);  // not in its own list
  CHECK(mets.find("data/original-captures/IMG_0001.dng") != std::string::npos);
}

TEST_CASE("a stylesheet cannot read local files or the network", "[mapping][safety]") {
  // A hostile stylesheet in place of the installed one (resources are looked up in
  // $SURROGATE_RESOURCES first) tries document() on a local file and on a URL.
  const fs::path root = freshDir("hostile");
  fs::create_directories(root / "xslt");
  const std::string secret = "surrogate-secret-" + std::to_string(::getpid());
  std::ofstream(root / "secret.xml") << "<s>" << secret << "</s>";
  for (const std::string& target : {"file://" + (root / "secret.xml").string(), (root / "secret.xml").string(),
                                    std::string("http://127.0.0.1:9/x.xml")}) {
    std::ofstream(root / "xslt/carrier-to-crm.xsl")
        << "<xsl:stylesheet version=\"1.0\" xmlns:xsl=\"http://www.w3.org/1999/XSL/Transform\""
           " xmlns:rdf=\"http://www.w3.org/1999/02/22-rdf-syntax-ns#\">"
           "<xsl:template match=\"/\"><rdf:RDF><xsl:value-of select=\"document('"
        << target << "')\"/></rdf:RDF></xsl:template></xsl:stylesheet>";
    ::setenv("SURROGATE_RESOURCES", root.c_str(), 1);
    std::string out;
    try {
      out = mapping::deriveCrm("<carrier xmlns=\"urn:surrogate:carrier:1\"/>");
    } catch (const Error&) {
      // refused: fine
    }
    ::unsetenv("SURROGATE_RESOURCES");
    INFO(target);
    CHECK(out.find(secret) == std::string::npos);
  }
}

TEST_CASE("the stylesheets and schemas to ship are all installed", "[mapping]") {
  // In the source tree, and in the list of data files the install rules install and an
  // installed program checks for (SURROGATE_DATA_FILES, core/resources.h).
  const std::vector<std::string>& installed = dataFileNames();
  for (const std::string& rel : mapping::packagedResources()) {
    INFO(rel);
    CHECK(fs::exists(std::string(SURROGATE_SOURCE_DIR) + "/" + rel));
    CHECK(std::find(installed.begin(), installed.end(), rel) != installed.end());
  }
  CHECK(mapping::crmStylesheetPath().filename() == "carrier-to-crm.xsl");
  CHECK(mapping::libxsltVersion() == LIBXSLT_DOTTED_VERSION);  // the headers built against
}

TEST_CASE("command runs become PREMIS events with their command line, outcome, notes and agents", "[mapping][mets][runs]") {
  const Sample s = sampleWithHistory("mets-runs");
  CHECK_NOTHROW(carrier::parseCarrier(s.carrierXml, "patched carrier.xml"));  // the sample is schema-valid
  const std::string mets = mapping::deriveMets(s.carrierXml, s.facts);
  CHECK_NOTHROW(mapping::validateMets(mets, "mets.xml"));

  // One event per run, identifiers apart from the steps' (event-s1) and the package's.
  CHECK(count(mets, ">metadata modification</premis:eventType>") == 3);
  for (const std::string& id : {"r1", "r2", "r3"}) {
    INFO(id);
    CHECK(count(mets, "<mets:digiprovMD ID=\"event-run-" + id + "\">") == 1);
    CHECK(count(mets, "<premis:eventIdentifierValue>event-run-" + id + "</premis:eventIdentifierValue>") == 1);
    // carrier.xml, the record each run rewrote, links back to the run.
    CHECK(count(mets, "<premis:linkingEventIdentifierValue>event-run-" + id + "</premis:linkingEventIdentifierValue>") == 1);
  }
  CHECK(mets.find("<premis:eventDateTime>2026-01-02T10:00:00Z</premis:eventDateTime>") != std::string::npos);
  // The command line, arguments with spaces (or empty) quoted.
  CHECK(mets.find("<premis:eventDetail>surrogate run --quiet</premis:eventDetail>") != std::string::npos);
  CHECK(mets.find("<premis:eventDetail>surrogate lights --sphere 339,57,45 --reason \"cut by frame\" \"\"</premis:eventDetail>") != std::string::npos);
  CHECK(mets.find("surrogate run --exclude IMG_0003 --reason \"the flash did not fire\" --accept-changed") != std::string::npos);
  // Outcomes: the sample's 5 successes (capture, 2 steps, digests, packaging) plus r1 and r2.
  CHECK(count(mets, "<premis:eventOutcome>success</premis:eventOutcome>") == 7);
  CHECK(count(mets, "<premis:eventOutcome>failure</premis:eventOutcome>") == 1);
  CHECK(mets.find("<premis:eventOutcomeDetailNote>failed: sphere 0 lies outside the frame</premis:eventOutcomeDetailNote>") != std::string::npos);
  CHECK(mets.find("<premis:eventOutcomeDetailNote>manual-sphere 0 = 339,57,45: cut by frame</premis:eventOutcomeDetailNote>") != std::string::npos);
  // The person who ran it (an agent even when named nowhere else: Eli Park) and the Surrogate
  // software.
  CHECK(mets.find("<premis:agentName>Eli Park</premis:agentName>") != std::string::npos);
  CHECK(mets.find("<premis:linkingAgentIdentifierValue>Eli Park</premis:linkingAgentIdentifierValue>") != std::string::npos);
  // Each run's person, and the person of the run that made the current state (r2, Dee Ortiz)
  // as the operator of the two steps that ran.
  CHECK(count(mets, "<premis:linkingAgentRole>implementer</premis:linkingAgentRole>") == 5);
  for (const std::string& id : {"r1", "r2", "r3"}) {
    const auto from = mets.find("<mets:digiprovMD ID=\"event-run-" + id + "\">");
    REQUIRE(from != std::string::npos);
    const std::string event = mets.substr(from, mets.find("</mets:digiprovMD>", from) - from);
    INFO(event);
    const auto software = event.find("<premis:linkingAgentIdentifierValue>Surrogate 0.1.0</premis:linkingAgentIdentifierValue>");
    REQUIRE(software != std::string::npos);
    CHECK(event.find("<premis:linkingAgentRole>executing program</premis:linkingAgentRole>", software) != std::string::npos);
    CHECK(event.find("<premis:linkingObjectIdentifierValue>data/assembly-files/carrier.xml</premis:linkingObjectIdentifierValue>") != std::string::npos);
  }
  // The last completed run (r2; r3 failed and left the record as it was) made the current steps.
  const auto r2 = mets.find("ID=\"event-run-r2\"");
  const auto r3 = mets.find("ID=\"event-run-r3\"");
  const auto made = mets.find("made the record's current state, pipeline steps: event-s1 event-s2");
  REQUIRE(made != std::string::npos);
  CHECK((r2 < made && made < r3));
  CHECK(count(mets, "made the record's current state") == 1);
  // The accept-changed-original intervention, with the bytes it accepts.
  CHECK(mets.find("intervention accept-changed-original on original-captures/IMG_0002.dng = " + std::string(kAcceptedHash) +
                  " by Dee Ortiz at 2026-01-02T10:00:00Z: re-exported by the museum") != std::string::npos);
  // A file the capture brings but the pipeline does not use: fileGrp "other", with its carrier id.
  const auto other = mets.find("<mets:fileGrp ID=\"fileGrp-other\" USE=\"other\">");
  REQUIRE(other != std::string::npos);
  const auto notes = mets.find("xlink:href=\"data/notes/session notes.txt\"");
  REQUIRE(notes != std::string::npos);
  CHECK(other < notes);
  CHECK(mets.find("<premis:objectIdentifierValue>f11</premis:objectIdentifierValue>") != std::string::npos);
  // In the structMap, as the folder and the file it is.
  CHECK(mets.find("<mets:div TYPE=\"Directory\" LABEL=\"notes\">\n        <mets:div TYPE=\"Item\" LABEL=\"session notes.txt\">\n"
                  "          <mets:fptr FILEID=\"file-f11\"/>") != std::string::npos);
}

TEST_CASE("a carrier without runs has no run events", "[mapping][mets][runs]") {
  const Sample s = sample("mets-no-runs");
  const std::string mets = mapping::deriveMets(s.carrierXml, s.facts);
  CHECK(mets.find("event-run-") == std::string::npos);
  CHECK(mets.find("metadata modification") == std::string::npos);
  CHECK(mapping::deriveCrm(s.carrierXml).find("/run/") == std::string::npos);
}

TEST_CASE("command runs become CIDOC-CRM activities of the session, in order, by a person", "[mapping][crm][runs]") {
  const Sample s = sampleWithHistory("crm-runs");
  const std::string crm = mapping::deriveCrm(s.carrierXml);
  CHECK_NOTHROW(mapping::checkRdfWellFormed(crm, "crm.rdf"));
  const fs::path file = s.capture.parent_path() / "crm.rdf";
  std::ofstream(file, std::ios::binary) << crm;
  const std::string parsed = run("rapper -q -i rdfxml -o ntriples " + file.string());
  REQUIRE(parsed.find("<http://www.w3.org/1999/02/22-rdf-syntax-ns#type>") != std::string::npos);

  const std::string base = "urn:surrogate:capture:" + digestFile(s.capture / "original-captures/IMG_0001.dng").sha256 + "/";
  const std::string crmNs = "http://www.cidoc-crm.org/cidoc-crm/";
  const auto triple = [&](const std::string& subject, const std::string& property, const std::string& object) {
    return parsed.find("<" + base + subject + "> <" + crmNs + property + "> " + object + " .") != std::string::npos;
  };
  const auto node = [&](const std::string& rel) { return "<" + base + rel + ">"; };
  for (const std::string& id : {"r1", "r2", "r3"}) {
    INFO(id);
    CHECK(parsed.find(node("run/" + id) + " <http://www.w3.org/1999/02/22-rdf-syntax-ns#type> <" + crmNs + "E7_Activity> .") != std::string::npos);
    CHECK(triple("session", "P9_consists_of", node("run/" + id)));
    CHECK(triple("run/" + id, "P2_has_type", node("type/surrogate-run")));
    CHECK(triple("run/" + id, "P4_has_time-span", node("run/" + id + "/time")));
  }
  CHECK(parsed.find(node("run/r3") + " <http://www.w3.org/2000/01/rdf-schema#label> \"surrogate lights (r3)\" .") != std::string::npos);
  CHECK(triple("run/r2", "P134_continued", node("run/r1")));
  CHECK(triple("run/r3", "P134_continued", node("run/r2")));
  CHECK_FALSE(parsed.find(node("run/r1") + " <" + crmNs + "P134_continued>") != std::string::npos);
  CHECK(triple("run/r2", "P14_carried_out_by", node("person/Dee_Ortiz")));
  CHECK(triple("run/r3", "P14_carried_out_by", node("person/Ana_Silva")));
  CHECK(triple("run/r1", "P14_carried_out_by", node("person/Eli_Park")));
  CHECK(parsed.find(node("person/Eli_Park") + " <http://www.w3.org/1999/02/22-rdf-syntax-ns#type> <" + crmNs + "E21_Person> .") != std::string::npos);
  CHECK(triple("run/r3", "P2_has_type", node("type/run-outcome/failed")));
  CHECK(triple("run/r2", "P2_has_type", node("type/run-outcome/completed")));
  CHECK(triple("run/r3", "P2_has_type", node("type/command/lights")));
  CHECK(triple("run/r3/time", "P82a_begin_of_the_begin", "\"2026-01-03T08:00:00Z\"^^<http://www.w3.org/2001/XMLSchema#dateTime>"));
  CHECK(triple("run/r3/time", "P82b_end_of_the_end", "\"2026-01-03T08:00:01Z\"^^<http://www.w3.org/2001/XMLSchema#dateTime>"));
  CHECK(triple("run/r3", "P3_has_note", "\"command line: surrogate lights --sphere 339,57,45 --reason \\\"cut by frame\\\" \\\"\\\"\""));
  CHECK(triple("run/r3", "P3_has_note", "\"failed: sphere 0 lies outside the frame\""));
  CHECK(triple("run/r3", "P3_has_note", "\"outcome: failed\""));
  // The last completed run made the current steps; the failed one after it did not.
  CHECK(triple("run/r2", "P9_consists_of", node("step/s1")));
  CHECK(triple("run/r2", "P9_consists_of", node("step/s2")));
  CHECK_FALSE(triple("run/r3", "P9_consists_of", node("step/s1")));
  CHECK_FALSE(triple("run/r1", "P9_consists_of", node("step/s1")));
  // accept-changed-original: the bytes accepted; the "other" file's role.
  CHECK(triple("step/s1/intervention/2", "P2_has_type", node("type/intervention/accept-changed-original")));
  CHECK(triple("step/s1/intervention/2", "P3_has_note", "\"accepted: the file as it is now, " + std::string(kAcceptedHash) + "\""));
  CHECK(triple("file/f11", "P2_has_type", node("type/role/other")));
  CHECK(mapping::deriveCrm(s.carrierXml) == crm);
}

// Issue 14: the derived metadata read as a repository's ingest reads it (archival_checks.h).
TEST_CASE("PREMIS in METS of a carrier with history: every link resolves, each agent and event once", "[mapping][mets][premis]") {
  const Sample s = sampleWithHistory("premis-links");
  const std::string mets = mapping::deriveMets(s.carrierXml, s.facts);
  CHECK_NOTHROW(mapping::validateMets(mets, "mets.xml"));
  const archival::Premis p = archival::readPremis(mets);
  for (const std::string& problem : archival::linkProblems(p)) FAIL_CHECK(problem);
  // The Surrogate of the header is also the packer: one agent, not two.
  CHECK(count(mets, "<premis:agentIdentifierValue>Surrogate 0.1.0</premis:agentIdentifierValue>") == 1);
  // One agent per distinct stage component and version.
  std::set<std::string> stageAgents;
  for (const auto& a : p.agents)
    if (a.value.rfind("Surrogate ", 0) == 0 && a.value != "Surrogate 0.1.0") CHECK(stageAgents.insert(a.value).second);
  // Every payload file has a MIMETYPE, those the carrier does not describe by their name.
  REQUIRE(p.files.size() == s.facts.payload.size());
  for (const auto& [href, mime] : p.files) {
    INFO(href);
    CHECK_FALSE(mime.empty());
  }
  CHECK(mets.find("MIMETYPE=\"text/plain\"") != std::string::npos);
  // The step that made the result files is their derivation event, with its sources.
  const std::vector<std::string> derived = {"data/finished-files/ptm-lrgb.ptm"};
  for (const std::string& problem : archival::derivationProblems(p, derived)) FAIL_CHECK(problem);
}

TEST_CASE("a carrier without rights or licence, as older versions wrote, maps to a statement that none was recorded", "[mapping][mets][rights]") {
  const Sample s = sample("no-rights");
  REQUIRE(s.carrierXml.find("<rights>") == std::string::npos);
  CHECK_NOTHROW(carrier::parseCarrier(s.carrierXml, "old carrier.xml"));
  const std::string mets = mapping::deriveMets(s.carrierXml, s.facts);
  CHECK_NOTHROW(mapping::validateMets(mets, "mets.xml"));
  CHECK(count(mets, "<premis:rightsStatement>") == 1);
  CHECK(mets.find("<premis:otherRightsBasis>unknown</premis:otherRightsBasis>") != std::string::npos);
  CHECK(mets.find("<dc:rights>") == std::string::npos);
  CHECK(mapping::deriveCrm(s.carrierXml).find("E30_Right") == std::string::npos);
}

TEST_CASE("rights and licence in the carrier header become PREMIS rights, METS rightsMD, Dublin Core and an E30 Right", "[mapping][mets][crm][rights]") {
  const fs::path capture = samplecapture::make(freshDir("rights"));
  std::string xml = slurp(capture / "assembly-files/carrier.xml");
  const auto at = xml.find("    <machine ");
  REQUIRE(at != std::string::npos);
  xml.insert(at, "    <rights>Images: Museum of Stelae; research use only</rights>\n"
                 "    <license>https://creativecommons.org/licenses/by-nc/4.0/</license>\n");
  const auto meta = xml.find("    <rights>");
  xml.insert(meta, "    <meta key=\"Subject\">funerary stela</meta>\n    <meta key=\"Description\">limestone, 3rd c. BC</meta>\n");
  std::ofstream(capture / "assembly-files/carrier.xml", std::ios::binary) << xml;
  const Sample s = sampleOf(capture);
  const carrier::Carrier c = carrier::parseCarrier(s.carrierXml, "carrier.xml");  // the schema takes them
  CHECK(c.header.rights == "Images: Museum of Stelae; research use only");
  CHECK(c.header.license == "https://creativecommons.org/licenses/by-nc/4.0/");
  CHECK(carrier::toXml(c).find("<license>https://creativecommons.org/licenses/by-nc/4.0/</license>") != std::string::npos);

  const std::string mets = mapping::deriveMets(s.carrierXml, s.facts);
  CHECK_NOTHROW(mapping::validateMets(mets, "mets.xml"));
  CHECK(mets.find("<mets:rightsMD ID=\"rights\">") != std::string::npos);
  CHECK(mets.find("<premis:rightsBasis>license</premis:rightsBasis>") != std::string::npos);
  CHECK(mets.find("<premis:licenseDocumentationIdentifierValue>https://creativecommons.org/licenses/by-nc/4.0/</premis:licenseDocumentationIdentifierValue>") != std::string::npos);
  CHECK(mets.find("<premis:otherRightsNote>Images: Museum of Stelae; research use only</premis:otherRightsNote>") != std::string::npos);
  CHECK(count(mets, "<premis:linkingRightsStatementIdentifierValue>") == 2);  // from the intellectual entity
  const archival::Premis p = archival::readPremis(mets);
  for (const std::string& problem : archival::linkProblems(p)) FAIL_CHECK(problem);
  // Dublin Core beside the CRM pointer; the structMap's top div names both.
  CHECK(mets.find("<mets:mdWrap MDTYPE=\"DC\"") != std::string::npos);
  CHECK(mets.find("DMDID=\"dmd-dc dmd-crm\"") != std::string::npos);
  for (const std::string& dc : {std::string("<dc:title>Stela 12 &amp; &lt;friends&gt;</dc:title>"), std::string("<dc:subject>funerary stela</dc:subject>"),
                                std::string("<dc:description>limestone, 3rd c. BC</dc:description>"),
                                std::string("<dc:rights>Images: Museum of Stelae; research use only</dc:rights>"),
                                std::string("<dc:rights>https://creativecommons.org/licenses/by-nc/4.0/</dc:rights>"),
                                std::string("<dc:date>2026-01-01</dc:date>"), std::string("<dc:type>Image</dc:type>")}) {
    INFO(dc);
    CHECK(mets.find(dc) != std::string::npos);
  }
  CHECK(mets.find("<dc:creator>") != std::string::npos);

  const std::vector<archival::Triple> triples = archival::rdfTriples(mapping::deriveCrm(s.carrierXml), capture.parent_path().string());
  int subject = 0;
  for (const auto& t : triples)
    if (t.p == "http://www.cidoc-crm.org/cidoc-crm/P104_is_subject_to") ++subject;
  CHECK(subject == static_cast<int>(c.files.size()));
  for (const std::string& problem :
       archival::crmTermProblems(triples, std::string(SURROGATE_SOURCE_DIR) + "/tests/mapping/data/crm-terms.tsv"))
    FAIL_CHECK(problem);
}

TEST_CASE("every CRM class and property of a carrier with history keeps the CRM 7.1.3 and CRMdig domains and ranges", "[mapping][crm][terms]") {
  const Sample s = sampleWithHistory("crm-terms");
  const std::string crm = mapping::deriveCrm(s.carrierXml);
  const std::vector<archival::Triple> triples = archival::rdfTriples(crm, s.capture.parent_path().string());
  REQUIRE(triples.size() > 150);
  for (const std::string& problem :
       archival::crmTermProblems(triples, std::string(SURROGATE_SOURCE_DIR) + "/tests/mapping/data/crm-terms.tsv"))
    FAIL_CHECK(problem);
  for (const std::string& problem : archival::crmDerivationProblems(triples)) FAIL_CHECK(problem);
  // The versions targeted are stated in the document.
  CHECK(crm.find("CIDOC-CRM 7.1.3") != std::string::npos);
  CHECK(crm.find("CRMdig 5.0") != std::string::npos);
  CHECK(crm.find("https://cidoc-crm.org/rdfs/7.1.3/CIDOC_CRM_v7.1.3.rdfs") != std::string::npos);
}

TEST_CASE("the term check catches a property used outside its domain", "[mapping][crm][terms]") {
  // P138_represents on a node that is only a D9 (its domain is E36), and an unknown class.
  const std::string nt =
      "<urn:x:f> <http://www.w3.org/1999/02/22-rdf-syntax-ns#type> <http://www.cidoc-crm.org/extensions/crmdig/D9_Data_Object> .\n"
      "<urn:x:o> <http://www.w3.org/1999/02/22-rdf-syntax-ns#type> <http://www.cidoc-crm.org/cidoc-crm/E22_Human-Made_Object> .\n"
      "<urn:x:f> <http://www.cidoc-crm.org/cidoc-crm/P138_represents> <urn:x:o> .\n"
      "<urn:x:g> <http://www.w3.org/1999/02/22-rdf-syntax-ns#type> <http://www.cidoc-crm.org/cidoc-crm/E999_Nothing> .\n";
  const auto problems = archival::crmTermProblems(archival::parseNTriples(nt),
                                                  std::string(SURROGATE_SOURCE_DIR) + "/tests/mapping/data/crm-terms.tsv");
  REQUIRE(problems.size() == 2);
  CHECK(problems[0].find("E999_Nothing") != std::string::npos);
  CHECK(problems[1].find("P138_represents: subject urn:x:f is not a E36_Visual_Item") != std::string::npos);
}

namespace {
// The sample capture with prior work another tool left: a .ptm in finished-files/ (what its
// header says recorded as madeBy) and an .lp in assembly-files/ that says nothing of its maker.
Sample sampleWithPriorWork(const std::string& name) {
  const fs::path capture = samplecapture::make(freshDir(name));
  const std::string ptm = "PTM_1.2\nPTM_FORMAT_LRGB\n1\n1\n1 1 1 1 1 1\n0 0 0 0 0 0\n" + std::string(9, '\x40');
  const std::string lp = "1\r\njpeg-exports\\IMG_0001.jpg 0 0 1\r\n";
  fs::create_directories(capture / "finished-files/rtibuilder");
  std::ofstream(capture / "finished-files/rtibuilder/stela.ptm", std::ios::binary) << ptm;
  std::ofstream(capture / "assembly-files/stela.lp", std::ios::binary) << lp;
  std::string xml = slurp(capture / "assembly-files/carrier.xml");
  const auto where = xml.find("  </files>");
  REQUIRE(where != std::string::npos);
  xml.insert(where,
             "    <file id=\"f90\" path=\"finished-files/rtibuilder/stela.ptm\" role=\"prior\" size=\"" +
                 std::to_string(ptm.size()) + "\" sha256=\"" + sha256Hex(ptm) +
                 "\" format=\"PTM_FORMAT_LRGB\" mediaType=\"application/x-ptm\" priorKind=\"rti\" "
                 "madeBy=\"PTM_1.2 PTM_FORMAT_LRGB\"/>\n"
                 "    <file id=\"f91\" path=\"assembly-files/stela.lp\" role=\"prior\" size=\"" +
                 std::to_string(lp.size()) + "\" sha256=\"" + sha256Hex(lp) +
                 "\" format=\"LP\" mediaType=\"text/plain\" priorKind=\"lp\"/>\n");
  std::ofstream(capture / "assembly-files/carrier.xml", std::ios::binary) << xml;
  return sampleOf(capture);
}
}  // namespace

TEST_CASE("prior work maps to its own METS group and to objects no Surrogate event made", "[mapping][mets][crm][prior]") {
  const Sample s = sampleWithPriorWork("prior-work");
  CHECK_NOTHROW(carrier::parseCarrier(s.carrierXml, "carrier.xml"));  // valid against xsd/carrier.xsd
  const std::string mets = mapping::deriveMets(s.carrierXml, s.facts);
  CHECK_NOTHROW(mapping::validateMets(mets, "mets.xml"));
  const archival::Premis p = archival::readPremis(mets);
  for (const std::string& problem : archival::linkProblems(p)) FAIL_CHECK(problem);
  const auto group = mets.find("<mets:fileGrp ID=\"fileGrp-prior-work\" USE=\"prior-work\">");
  REQUIRE(group != std::string::npos);
  const std::string members = mets.substr(group, mets.find("</mets:fileGrp>", group) - group);
  CHECK(count(members, "<mets:file ") == 2);
  CHECK(members.find("xlink:href=\"data/finished-files/rtibuilder/stela.ptm\"") != std::string::npos);
  CHECK(members.find("xlink:href=\"data/assembly-files/stela.lp\"") != std::string::npos);
  CHECK(mets.find("<premis:significantPropertiesValue>PTM_1.2 PTM_FORMAT_LRGB</premis:significantPropertiesValue>") != std::string::npos);
  CHECK(mets.find("<premis:significantPropertiesValue>not known: the file does not say</premis:significantPropertiesValue>") != std::string::npos);
  // Derived from nothing on record: the result the sample's RtiFit made still is, the prior
  // .ptm is not.
  for (const std::string& problem : archival::derivationProblems(p, {"data/finished-files/ptm-lrgb.ptm"})) FAIL_CHECK(problem);
  CHECK(archival::derivationProblems(p, {"data/finished-files/rtibuilder/stela.ptm"}) ==
        std::vector<std::string>{"data/finished-files/rtibuilder/stela.ptm has no PREMIS path back to a photograph"});

  const std::string crm = mapping::deriveCrm(s.carrierXml);
  const std::vector<archival::Triple> triples = archival::rdfTriples(crm, s.capture.parent_path().string());
  for (const std::string& problem :
       archival::crmTermProblems(triples, std::string(SURROGATE_SOURCE_DIR) + "/tests/mapping/data/crm-terms.tsv"))
    FAIL_CHECK(problem);
  for (const std::string& problem : archival::crmDerivationProblems(triples)) FAIL_CHECK(problem);
  CHECK(crm.find("the file says of its making: PTM_1.2 PTM_FORMAT_LRGB") != std::string::npos);
  CHECK(crm.find("prior work (lp): made outside Surrogate") != std::string::npos);
}
