// The stylesheets: METS+PREMIS valid against the vendored schemas offline, CIDOC-CRM parsed by
// rapper with the key classes and properties, deterministic output, safe processing.
#include <catch2/catch.hpp>

#include <unistd.h>

#include <array>
#include <atomic>
#include <cstdio>
#include <fstream>
#include <regex>

#include "archive/digest.h"
#include "core/error.h"
#include "mapping/mapping.h"
#include "sample_capture.h"
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

Sample sample(const std::string& name) {
  Sample s;
  s.capture = samplecapture::make(freshDir(name));
  s.carrierXml = slurp(s.capture / "assembly-files/carrier.xml");
  s.facts.packageId = "urn:sha256:" + archive::sha256Hex(s.carrierXml);
  s.facts.packagingTime = "2026-01-03T00:00:00Z";
  s.facts.softwareAgent = "Surrogate 0.1.0";
  std::vector<std::string> paths;
  for (auto it = fs::recursive_directory_iterator(s.capture); it != fs::recursive_directory_iterator(); ++it)
    if (it->is_regular_file()) paths.push_back(it->path().lexically_relative(s.capture).generic_string());
  std::sort(paths.begin(), paths.end());
  for (const std::string& p : paths) {
    const archive::FileDigests d = archive::digestFile(s.capture / p, true);
    s.facts.payload.push_back({"data/" + p, d.size, d.sha256, d.sha512});
  }
  return s;
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
  CHECK(count(mets, "<premis:object ") == static_cast<int>(s.facts.payload.size()));
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
  CHECK(mets.find("<premis:eventType>capture</premis:eventType>") != std::string::npos);
  CHECK(mets.find("<premis:eventType>message digest calculation</premis:eventType>") != std::string::npos);
  CHECK(mets.find("<premis:eventType>information package creation</premis:eventType>") != std::string::npos);
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
  noFileSecId.replace(noFileSecId.find("ID=\"file-1\""), 11, "ID=\"1-bad\"");
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
  CHECK(parsed.find("\"" + archive::digestFile(s.capture / "original-captures/IMG_0001.dng").sha256 + "\"") != std::string::npos);
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
  for (const std::string& rel : mapping::packagedResources()) {
    INFO(rel);
    CHECK(fs::exists(std::string(SURROGATE_SOURCE_DIR) + "/" + rel));
  }
  CHECK(mapping::crmStylesheetPath().filename() == "carrier-to-crm.xsl");
  CHECK_FALSE(mapping::libxsltVersion().empty());
}
