// deriveCrmTo / deriveMetsTo write the result while the stylesheet builds it and free it as they
// go: their bytes must be exactly the whole-tree serialisation (deriveCrm / deriveMets, which
// `surrogate pack` writes and xsltproc gives), or a verifier would call sound packages changed.
#include <catch2/catch.hpp>

#include <algorithm>
#include <cstdlib>
#include <fstream>
#include <stdexcept>
#include <string>

#include "carrier/carrier.h"
#include "core/digest.h"
#include "mapping/mapping.h"
#include "test_files.h"

using namespace surrogate;

namespace {

// A carrier of `files` originals (one ingest step listing them all), and payload facts for
// them: enough instructions for the result to be written out many times while it is built.
struct Large {
  std::string carrierXml;
  mapping::PackageFacts facts;
};

Large large(int files) {
  carrier::Carrier c = carrier::newCarrier("Streamed <mapping> & \"quotes\"", {{"A. Tester", "creator"}});
  c.header.meta.push_back({"Source-Organization", "Musée d'Orsay"});
  carrier::Step& ingest = c.addStep("CaptureIngest", "2");
  ingest.description = "Inventory of the capture";
  ingest.setParam("source", "auto");
  carrier::Result result;
  result.step = ingest.id;
  result.started = result.ended = c.header.created;
  Large out;
  for (int i = 0; i < files; ++i) {
    const std::string content = "image " + std::to_string(i);
    carrier::FileRecord f;
    f.id = "f" + std::to_string(i + 1);
    f.path = "original-captures/batch-" + std::to_string(i / 100) + "/IMG " + std::to_string(i + 1) + "é.jpg";
    f.role = "original";
    f.size = content.size();
    f.sha256 = sha256Hex(content);
    f.format = "JPEG";
    f.mediaType = "image/jpeg";
    out.facts.payload.push_back({"data/" + f.path, f.size, f.sha256, std::string(128, 'a')});
    c.files.push_back(f);
    result.add("input").set("file", f.id).set("kind", "image");
  }
  result.add("value").set("name", "images").set("value", std::to_string(files));
  c.data.push_back(std::move(result));
  std::sort(out.facts.payload.begin(), out.facts.payload.end(),
            [](const mapping::PayloadFile& a, const mapping::PayloadFile& b) { return a.path < b.path; });
  out.carrierXml = carrier::toXml(c);
  out.facts.packageId = "urn:sha256:" + sha256Hex(out.carrierXml);
  out.facts.packagingTime = "2026-01-03T00:00:00Z";
  out.facts.softwareAgent = "Surrogate 0.1.0";
  return out;
}

}  // namespace

TEST_CASE("deriveMetsTo and deriveCrmTo give, piece by piece, the bytes of deriveMets and deriveCrm",
          "[mapping]") {
  for (const int files : {0, 1, 7, 1500}) {
    CAPTURE(files);
    const Large l = large(files);
    std::string crm, mets;
    std::size_t pieces = 0;
    CHECK(mapping::deriveCrmTo(l.carrierXml, [&](const char* p, std::size_t n) { crm.append(p, n); }));
    CHECK(mapping::deriveMetsTo(l.carrierXml, l.facts, [&](const char* p, std::size_t n) {
      mets.append(p, n);
      ++pieces;
    }));
    const std::string wholeCrm = mapping::deriveCrm(l.carrierXml);
    const std::string wholeMets = mapping::deriveMets(l.carrierXml, l.facts);
    CHECK(crm.size() == wholeCrm.size());
    CHECK(crm == wholeCrm);
    CHECK(mets.size() == wholeMets.size());
    CHECK(mets == wholeMets);
    if (files == 1500) CHECK(pieces > 10);  // written while built, not at the end
  }
}

TEST_CASE("a derivation streamed into a sink that fails stops with the sink's error", "[mapping]") {
  const Large l = large(200);
  std::size_t given = 0;
  CHECK_THROWS_WITH(
      (void)mapping::deriveMetsTo(l.carrierXml, l.facts,
                                  [&](const char*, std::size_t n) {
                                    given += n;
                                    if (given > 100000) throw std::runtime_error("disk full");
                                  }),
      "disk full");
}

namespace {

// The bundled resources, with xslt/carrier-to-crm.xsl replaced by `stylesheet`, for as long as
// it lives (core/resources.h looks in $SURROGATE_RESOURCES first).
class OtherCrmStylesheet {
 public:
  explicit OtherCrmStylesheet(const std::string& stylesheet) {
    const std::filesystem::path root = testfiles::freshDir("streamed-stylesheet");
    std::filesystem::create_directories(root / "xslt");
    std::ofstream(root / "xslt/carrier-to-crm.xsl", std::ios::binary) << stylesheet;
    if (const char* old = std::getenv("SURROGATE_RESOURCES")) previous_ = old;
    ::setenv("SURROGATE_RESOURCES", root.c_str(), 1);
  }
  ~OtherCrmStylesheet() {
    if (previous_.empty()) ::unsetenv("SURROGATE_RESOURCES");
    else ::setenv("SURROGATE_RESOURCES", previous_.c_str(), 1);
  }

 private:
  std::string previous_;
};

// An RDF root that receives, after many element children, text (`textFirst` false) or whose
// first child is text (true).
std::string mixedContent(bool textFirst) {
  return std::string(R"(<xsl:stylesheet version="1.0" xmlns:xsl="http://www.w3.org/1999/XSL/Transform"
    xmlns:rdf="http://www.w3.org/1999/02/22-rdf-syntax-ns#" xmlns:c="urn:surrogate:carrier:1">
  <xsl:output method="xml" encoding="UTF-8" indent="yes"/>
  <xsl:template match="/">
    <rdf:RDF>)") + (textFirst ? "<xsl:text>head</xsl:text>" : "") + R"(
      <xsl:for-each select="//c:file"><rdf:Description rdf:about="{@path}"><n><xsl:value-of select="@id"/></n></rdf:Description></xsl:for-each>
      <xsl:text>tail</xsl:text>
    </rdf:RDF>
  </xsl:template>
</xsl:stylesheet>
)";
}

}  // namespace

TEST_CASE("a result whose text follows children already written indented is reported, not "
          "written wrong", "[mapping]") {
  const Large l = large(1500);
  for (const bool textFirst : {false, true}) {
    CAPTURE(textFirst);
    OtherCrmStylesheet other(mixedContent(textFirst));
    std::string streamed;
    const bool exact = mapping::deriveCrmTo(l.carrierXml, [&](const char* p, std::size_t n) { streamed.append(p, n); });
    const std::string whole = mapping::deriveCrm(l.carrierXml);
    REQUIRE(whole.find("tail") != std::string::npos);
    if (textFirst) {
      // Text from the start: nothing is indented under the root, which streams exactly.
      CHECK(exact);
      CHECK(streamed == whole);
    } else {
      // The children were written indented before the text came: the caller must derive again.
      CHECK_FALSE(exact);
      CHECK(streamed != whole);
    }
  }
}

namespace {

std::string xmlAttribute(const std::string& s) {
  std::string out;
  for (const char ch : s) {
    if (ch == '&') out += "&amp;";
    else if (ch == '<') out += "&lt;";
    else if (ch == '"') out += "&quot;";
    else out += ch;
  }
  return out;
}

}  // namespace

// The program names each entry of the payload list after its file group (mapping.cpp); the
// stylesheet's documented input, for anyone deriving by hand, is <file> entries whose groups
// it looks up itself. Both must give the same METS: xsltproc on the bundled stylesheet with a
// list of <file> entries is the reference.
TEST_CASE("METS from the grouped payload list of the program equals xsltproc on a plain one", "[mapping]") {
  Large l = large(40);
  carrier::Carrier c = carrier::parseCarrier(l.carrierXml, "carrier.xml");
  const char* roles[] = {"original", "export", "sidecar", "prior", "other", "assembly", "result", "lp"};
  for (std::size_t i = 0; i < c.files.size(); ++i) c.files[i].role = roles[i % 8];
  c.files[5].priorKind = "rti";
  l.carrierXml = carrier::toXml(c);
  // Payload files the carrier does not list (its own file, the report): group "other".
  l.facts.payload.push_back({"data/assembly-files/carrier.xml", l.carrierXml.size(), sha256Hex(l.carrierXml),
                             std::string(128, 'b')});
  l.facts.payload.push_back({"data/finished-files/report.html", 12, std::string(64, 'c'), std::string(128, 'd')});
  // One file whose size differs from its record (given in full in the list).
  l.facts.payload[3].size += 1;
  std::sort(l.facts.payload.begin(), l.facts.payload.end(),
            [](const mapping::PayloadFile& a, const mapping::PayloadFile& b) { return a.path < b.path; });

  const std::string ours = mapping::deriveMets(l.carrierXml, l.facts);

  const std::filesystem::path dir = testfiles::freshDir("payload-groups");
  std::ofstream(dir / "carrier.xml", std::ios::binary) << l.carrierXml;
  {
    std::ofstream list(dir / "payload.xml", std::ios::binary);
    list << "<payload>";
    for (const mapping::PayloadFile& p : l.facts.payload)
      list << "<file path=\"" << xmlAttribute(p.path) << "\" size=\"" << p.size << "\" sha256=\"" << p.sha256
           << "\" sha512=\"" << p.sha512 << "\"/>";
    list << "</payload>\n";
  }
  const std::string command =
      "xsltproc --stringparam package-id '" + l.facts.packageId + "' --stringparam packaging-time '" +
      l.facts.packagingTime + "' --stringparam software-agent '" + l.facts.softwareAgent +
      "' --stringparam payload-uri '" + (dir / "payload.xml").string() + "' '" SURROGATE_SOURCE_DIR
      "/xslt/carrier-to-mets.xsl' '" + (dir / "carrier.xml").string() + "' > '" + (dir / "mets.xml").string() + "'";
  REQUIRE(std::system(command.c_str()) == 0);
  const std::string reference = testfiles::slurp(dir / "mets.xml");
  REQUIRE(reference.find("USE=\"prior-work\"") != std::string::npos);
  REQUIRE(reference.find("USE=\"other\"") != std::string::npos);
  CHECK(ours.size() == reference.size());
  CHECK(ours == reference);
}
