// The places of the bag's files in an E-ARK SIP (docs/package.md, "The package as an E-ARK
// SIP"), both ways: verify puts the bag back together with bagPathOf, so every file a bag
// can hold must come back to where it was, the tag files other versions may add included.
#include <catch2/catch.hpp>

#include "archive/eark_layout.h"

using surrogate::archive::bagPathOf;
using surrogate::archive::sipPathOf;

TEST_CASE("E-ARK SIP places: each bag file where docs/package.md puts it, and back", "[layouts]") {
  const std::vector<std::pair<std::string, std::string>> places = {
      {"data/original-captures/IMG_1.dng", "representations/rep1/data/original-captures/IMG_1.dng"},
      {"data/assembly-files/carrier.xml", "representations/rep1/data/assembly-files/carrier.xml"},
      {"metadata/mets.xml", "metadata/preservation/mets.xml"},
      {"metadata/crm.rdf", "metadata/descriptive/crm.rdf"},
      {"metadata/xsd/mets-1.12.1.xsd", "schemas/mets-1.12.1.xsd"},
      {"metadata/mappings/carrier-to-mets.md", "documentation/mappings/carrier-to-mets.md"},
      {"metadata/xslt/carrier-to-crm.xsl", "documentation/xslt/carrier-to-crm.xsl"},
      {"metadata/formats.md", "documentation/formats.md"},
      {"bagit.txt", "metadata/other/bagit/bagit.txt"},
      {"bag-info.txt", "metadata/other/bagit/bag-info.txt"},
      {"tagmanifest-sha512.txt", "metadata/other/bagit/tagmanifest-sha512.txt"},
      {"README.txt", "metadata/other/bagit/README.txt"},
  };
  for (const auto& [bag, sip] : places) {
    INFO(bag);
    CHECK(sipPathOf(bag) == sip);
    CHECK(bagPathOf(sip) == bag);
  }
  // The METS files and anything no bag file maps to have no place in the bag.
  for (const char* sip : {"METS.xml", "representations/rep1/METS.xml", "representations/rep2/data/x",
                          "metadata/other/bagit/", "metadata/preservation/premis.xml", "extra.txt"}) {
    INFO(sip);
    CHECK(!bagPathOf(sip));
  }
}
