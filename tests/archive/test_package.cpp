// A capture packed as an archival package: layout per docs/package.md, the carrier's hashes checked
// while packing, metadata derived and valid, the package explains itself.
#include <catch2/catch.hpp>

#include <unistd.h>

#include <atomic>
#include <cstdlib>
#include <fstream>

#include "archive/package.h"
#include "bag_check.h"
#include "carrier/carrier.h"
#include "core/error.h"
#include "mapping/mapping.h"
#include "sample_capture.h"
#include "test_files.h"

namespace fs = std::filesystem;
using namespace surrogate;
using namespace surrogate::archive;
using testfiles::freshDir;
using testfiles::slurp;

TEST_CASE("a packed capture has the docs/package.md layout and is a valid bag", "[archive][package]") {
  const fs::path dir = freshDir("layout");
  const fs::path capture = samplecapture::make(dir);
  const PackResult r = packCapture(capture, dir / "pkg.zip");
  const bagcheck::BagFiles bag = bagcheck::readBag(dir / "pkg.zip");
  const auto problems = bagcheck::validate(bag);
  INFO((problems.empty() ? std::string() : problems.front()));
  CHECK(problems.empty());
  for (const char* p : {"data/original-captures/IMG_0001.dng", "data/original-captures/IMG_0001.xmp",
                        "data/jpeg-exports/IMG_0003.jpg", "data/assembly-files/carrier.xml",
                        "data/assembly-files/lights.lp", "data/assembly-files/spheres.png",
                        "data/finished-files/ptm-lrgb.ptm", "data/finished-files/report.html",
                        "metadata/crm.rdf", "metadata/mets.xml", "metadata/xslt/carrier-to-crm.xsl",
                        "metadata/xslt/carrier-to-mets.xsl", "metadata/xsd/mets-1.12.1.xsd",
                        "metadata/xsd/premis-3.0.xsd", "metadata/xsd/xlink.xsd", "metadata/xsd/carrier.xsd",
                        "metadata/mappings/carrier-to-crm.md", "metadata/mappings/carrier-to-mets.md"}) {
    INFO(p);
    CHECK(bag.files.count(p) == 1);
  }
  // Originals byte-identical; the carrier included as it is.
  CHECK(bag.files.at("data/original-captures/IMG_0002.dng") == slurp(capture / "original-captures/IMG_0002.dng"));
  CHECK(bag.files.at("data/assembly-files/carrier.xml") == slurp(capture / "assembly-files/carrier.xml"));
  CHECK(r.bag.payloadFiles == 13);  // the capture's 12 and data/ro-crate-metadata.json
  CHECK(r.packageId == "urn:sha256:" + bagcheck::sha256(slurp(capture / "assembly-files/carrier.xml")));

  // bag-info carries the user's metadata and what a verifier needs to re-derive mets.xml.
  const auto info = bagcheck::parseBagInfo(bag.files.at("bag-info.txt"));
  CHECK(info.find("Source-Organization")->second == "Museum of Tests");
  CHECK(info.find("External-Identifier")->second == "INV-42");
  CHECK(info.find("Contact-Name")->second == "Ana Silva");
  CHECK(info.find("Surrogate-Package-Identifier")->second == r.packageId);
  CHECK(info.find("Surrogate-Packaging-Time")->second == r.packagingTime);
  CHECK(info.count("Surrogate-Package-Identifier") == 1);
  CHECK(info.count("Surrogate-Packaging-Time") == 1);
  // The labels are packageInfo's, which the verifier compares bag-info.txt with.
  const PackageInfo expected =
      packageInfo(carrier::loadCarrier(capture / "assembly-files/carrier.xml"), r.packageId, r.packagingTime);
  for (const auto* list : {&expected.user, &expected.own})
    for (const auto& [label, value] : *list) {
      INFO(label);
      CHECK(info.count(label) == 1);
    }
  // A holder's field (pack --bag-info) may be any other label: not one of these, nor a
  // computed or Surrogate-* one.
  const carrier::Carrier recorded = carrier::loadCarrier(capture / "assembly-files/carrier.xml");
  CHECK_THAT(holderFieldProblem("source-organization", "Elsewhere", &recorded),
             Catch::Matchers::Contains("already written by Surrogate from the carrier"));
  CHECK_THAT(holderFieldProblem("External-Description", "x", &recorded),
             Catch::Matchers::Contains("already written by Surrogate from the carrier"));
  CHECK_THAT(holderFieldProblem("Surrogate-Anything", "x", &recorded), Catch::Matchers::Contains("written by Surrogate itself"));
  CHECK_THAT(holderFieldProblem("Internal-Sender-Identifier", "a\nb", &recorded), Catch::Matchers::Contains("line break"));
  CHECK(holderFieldProblem("Internal-Sender-Identifier", "accession 17", &recorded).empty());
  CHECK(holderFieldProblem("Source-Organization", "Elsewhere").empty());  // no carrier: the form only
  CHECK(isSurrogateLabel("payload-oxum", expected));
  CHECK(isSurrogateLabel("Contact-Name", expected));
  CHECK_FALSE(isSurrogateLabel("Contact-Email", expected));

  // The metadata is what the stylesheets give, and METS is valid.
  const std::string carrierXml = bag.files.at("data/assembly-files/carrier.xml");
  mapping::PackageFacts facts;
  facts.packageId = info.find("Surrogate-Package-Identifier")->second;
  CHECK(bag.files.at("metadata/crm.rdf") == mapping::deriveCrm(carrierXml, mapping::crmFactsOf(facts)));
  facts.packagingTime = info.find("Surrogate-Packaging-Time")->second;
  facts.softwareAgent = info.find("Bag-Software-Agent")->second;
  const auto m256 = bagcheck::parseManifest(bag.files.at("manifest-sha256.txt"));
  const auto m512 = bagcheck::parseManifest(bag.files.at("manifest-sha512.txt"));
  REQUIRE(m256.size() == m512.size());
  for (std::size_t i = 0; i < m256.size(); ++i)
    facts.payload.push_back({m256[i].second, bag.files.at(m256[i].second).size(), m256[i].first, m512[i].first});
  CHECK(bag.files.at("metadata/mets.xml") == mapping::deriveMets(carrierXml, facts));
  CHECK_NOTHROW(mapping::validateMets(bag.files.at("metadata/mets.xml"), "mets.xml"));
  // The shipped stylesheets are the ones used.
  CHECK(bag.files.at("metadata/xslt/carrier-to-mets.xsl") == slurp(mapping::metsStylesheetPath()));
}

TEST_CASE("two packs of a capture with SOURCE_DATE_EPOCH set are byte-identical", "[archive][package]") {
  ::setenv("SOURCE_DATE_EPOCH", "1700000000", 1);
  const fs::path dir = freshDir("repro");
  const fs::path capture = samplecapture::make(dir);
  fs::create_directories(dir / "a");
  fs::create_directories(dir / "b");
  for (const char* name : {"pkg.tar", "pkg.zip"}) {
    const PackResult r = packCapture(capture, dir / "a" / name);
    CHECK(r.packagingTime == "2023-11-14T22:13:20Z");
    packCapture(capture, dir / "b" / name);
    CHECK(slurp(dir / "a" / name) == slurp(dir / "b" / name));
  }
  ::unsetenv("SOURCE_DATE_EPOCH");
}

TEST_CASE("checkCarrier tells a complete carrier from a missing, failed or stale one", "[archive][package]") {
  const fs::path dir = freshDir("state");
  const fs::path capture = samplecapture::make(dir);
  CHECK(checkCarrier(capture).complete);

  SECTION("a recorded file changed size") {
    std::ofstream(capture / "finished-files/ptm-lrgb.ptm", std::ios::app) << "x";
    const CarrierState s = checkCarrier(capture);
    CHECK_FALSE(s.complete);
    CHECK(s.reason.find("ptm-lrgb.ptm") != std::string::npos);
  }
  SECTION("a step failed") {
    carrier::Carrier c = carrier::loadCarrier(capture / "assembly-files/carrier.xml");
    c.data.back().status = "failed";
    carrier::saveCarrier(c, capture / "assembly-files/carrier.xml");
    CHECK_FALSE(checkCarrier(capture).complete);
  }
  SECTION("no carrier") {
    fs::remove(capture / "assembly-files/carrier.xml");
    CHECK_FALSE(checkCarrier(capture).complete);
  }
}

TEST_CASE("a file whose content changed but not its size is caught while packing", "[archive][package]") {
  const fs::path dir = freshDir("stale");
  const fs::path capture = samplecapture::make(dir);
  {
    std::fstream f(capture / "original-captures/IMG_0002.dng", std::ios::in | std::ios::out | std::ios::binary);
    f.seekp(100);
    f.put('\x42');
  }
  CHECK(checkCarrier(capture).complete);  // cheap check: sizes only
  try {
    packCapture(capture, dir / "pkg.tar");
    FAIL("no error");
  } catch (const PayloadChanged& e) {
    CHECK(e.bagPath() == "data/original-captures/IMG_0002.dng");
  }
  CHECK_FALSE(fs::exists(dir / "pkg.tar"));
}

TEST_CASE("the payload is what the carrier records and the report, and no unrecorded file", "[archive][package]") {
  const fs::path dir = freshDir("payload");
  const fs::path capture = samplecapture::make(dir);
  // Left out by the documented rule: what operating systems leave, Surrogate's working area and
  // moved-aside results, and Surrogate's own interrupted writes in its output folders.
  std::ofstream(capture / "original-captures/.DS_Store") << "finder";
  std::ofstream(capture / "jpeg-exports/Thumbs.db") << "explorer";
  std::ofstream(capture / "original-captures/._IMG_0001.dng") << "appledouble";
  fs::create_directories(capture / ".surrogate");
  std::ofstream(capture / ".surrogate/lock") << "pid";
  fs::create_directories(capture / "superseded-files/r1/finished-files");
  std::ofstream(capture / "superseded-files/r1/finished-files/hsh3.rti") << "old result";
  std::ofstream(capture / "finished-files/.report.html.part-1-0") << "interrupted write";
  std::vector<std::string> paths;
  for (const PayloadSource& p : capturePayload(capture)) paths.push_back(p.bagPath);
  const carrier::Carrier c = carrier::loadCarrier(capture / "assembly-files/carrier.xml");
  CHECK(paths.size() == c.files.size() + 2);  // + the carrier and the report
  for (const carrier::FileRecord& f : c.files)
    CHECK(std::find(paths.begin(), paths.end(), "data/" + f.path) != paths.end());
  CHECK(std::find(paths.begin(), paths.end(), "data/finished-files/report.html") != paths.end());
  CHECK(std::find(paths.begin(), paths.end(), "data/assembly-files/carrier.xml") != paths.end());
  CHECK(checkCarrier(capture).complete);

  // Anything else is refused, named: a file the carrier does not describe is never bagged.
  std::ofstream(capture / "notes.txt") << "not recorded";
  std::ofstream(capture / "finished-files/hsh3.rti") << "a stale result";
  try {
    capturePayload(capture);
    FAIL("no error");
  } catch (const surrogate::Error& e) {
    CHECK(std::string(e.what()).find("notes.txt") != std::string::npos);
    CHECK(std::string(e.what()).find("finished-files/hsh3.rti") != std::string::npos);
  }
  const CarrierState state = checkCarrier(capture);
  CHECK_FALSE(state.complete);
  CHECK(state.unrecordedOutputs == std::vector<std::string>{"finished-files/hsh3.rti"});
}

TEST_CASE("a missing or resized original is an input problem, a missing result is not", "[archive][package]") {
  const fs::path dir = freshDir("inputs");
  const fs::path capture = samplecapture::make(dir);
  fs::remove(capture / "finished-files/ptm-lrgb.ptm");
  CarrierState state = checkCarrier(capture);
  CHECK_FALSE(state.complete);
  CHECK(state.inputProblem.empty());
  std::ofstream(capture / "original-captures/IMG_0002.dng", std::ios::app) << "x";
  state = checkCarrier(capture);
  CHECK(state.inputProblem.find("original-captures/IMG_0002.dng") != std::string::npos);
}

TEST_CASE("pack refuses names the package cannot hold before writing anything", "[archive][package]") {
  // A carrier may record such names (written before the capture scan refused them, or edited):
  // pack judges the payload by the rule of the scan and of verify (core/file_names.h).
  const fs::path dir = freshDir("unholdable");
  const fs::path capture = samplecapture::make(dir);
  carrier::Carrier c = carrier::loadCarrier(capture / "assembly-files/carrier.xml");
  fs::create_directories(capture / "notes");
  // (A control character the carrier cannot hold as it is: the scan refuses it, test_file_names.)
  for (const std::string name : {"notes/Readme.txt", "notes/README.txt", "notes/a\\b.txt", "notes/cafe\xCC\x81.txt"}) {
    std::ofstream(capture / name) << name;
    carrier::FileRecord f;
    f.path = name;
    f.role = "other";
    f.size = name.size();
    f.sha256 = bagcheck::sha256(name);
    f.format = "TXT";
    c.putFile(f);
  }
  carrier::saveCarrier(c, capture / "assembly-files/carrier.xml");
  for (const char* out : {"pkg.zip", "pkg.tar", "pkg"}) {
    INFO(out);
    try {
      packCapture(capture, dir / out);
      FAIL("no error");
    } catch (const surrogate::Error& e) {
      CHECK(e.kind() == ErrorKind::Input);
      const std::string m = e.message();
      CHECK(m.find("notes/README.txt  and  notes/Readme.txt") != std::string::npos);
      CHECK(m.find("notes/a\\b.txt") != std::string::npos);
      CHECK(m.find("notes/cafe\xCC\x81.txt") != std::string::npos);
      CHECK(m.find("NFD") != std::string::npos);
      CHECK(m.find("rename") != std::string::npos);
    }
    CHECK_FALSE(fs::exists(dir / out));
  }
  std::vector<std::string> left;
  for (const auto& e : fs::directory_iterator(dir)) left.push_back(e.path().filename().string());
  CHECK(left == std::vector<std::string>{"capture"});  // no temporary file either
}
