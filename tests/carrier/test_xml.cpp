#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <string>

#include <catch2/catch.hpp>

#include "carrier/xml.h"
#include "core/error.h"

using namespace surrogate;
namespace fs = std::filesystem;

TEST_CASE("well-formed XML passes and broken XML names the document") {
  xml::checkWellFormed("<a><b/></a>", "ok.xml");
  try {
    xml::checkWellFormed("<a><b></a>", "broken.xml");
    FAIL("accepted broken XML");
  } catch (const Error& e) {
    CHECK(e.file() == "broken.xml");
    CHECK(e.exitCode() == 1);
  }
}

TEST_CASE("entity-expansion bombs and external entities are refused") {
  const std::string laughs =
      "<?xml version=\"1.0\"?><!DOCTYPE lolz [<!ENTITY lol \"lol\">"
      "<!ENTITY lol2 \"&lol;&lol;&lol;&lol;&lol;&lol;&lol;&lol;&lol;&lol;\">"
      "<!ENTITY lol3 \"&lol2;&lol2;&lol2;&lol2;&lol2;&lol2;&lol2;&lol2;&lol2;&lol2;\">]>"
      "<lolz>&lol3;</lolz>";
  CHECK_THROWS_AS(xml::checkWellFormed(laughs, "bomb.xml"), Error);
  const std::string xxe =
      "<?xml version=\"1.0\"?><!DOCTYPE x [<!ENTITY e SYSTEM \"file:///etc/passwd\">]><x>&e;</x>";
  CHECK_THROWS_AS(xml::checkWellFormed(xxe, "xxe.xml"), Error);
}

TEST_CASE("the root element of a document is read with its attributes in order") {
  const xml::RootElement root = xml::readRootElement(
      "<?xml version=\"1.0\"?>\n<!-- a log -->\n<log:RTIBuilderLog xmlns:log=\"urn:x\" version=\"2.0.2\" "
      "tool=\"RTIBuilder &amp; PTMFitter\"><step/></log:RTIBuilderLog>",
      "log.xml");
  CHECK(root.name == "log:RTIBuilderLog");
  REQUIRE(root.attributes.size() == 2);
  CHECK(root.attributes[0] == std::make_pair(std::string("version"), std::string("2.0.2")));
  CHECK(root.attributes[1] == std::make_pair(std::string("tool"), std::string("RTIBuilder & PTMFitter")));
  CHECK_THROWS_AS(xml::readRootElement("<a><b></a>", "broken.xml"), Error);
  CHECK_THROWS_AS(xml::readRootElement("<!DOCTYPE a [<!ENTITY e \"x\">]><a>&e;</a>", "dtd.xml"), Error);
}

TEST_CASE("a document read whole keeps names, namespaces, prefixed attributes, text and children, and refuses too many elements") {
  const xml::Element root = xml::readElementTree(
      "<?xml version=\"1.0\"?>\n<r xmlns=\"urn:r\" xmlns:xl=\"urn:xl\">\n  <f xl:href=\"a\\b.jpg\" ID=\"1\"/>\n"
      "  <t>one &amp; two</t>\n  <t><![CDATA[<raw>]]></t>\n</r>",
      "tree.xml", 10);
  CHECK(root.name == "r");
  CHECK(root.namespaceUri == "urn:r");
  CHECK(root.text.empty());  // indentation between children is not text
  REQUIRE(root.children.size() == 3);
  CHECK(root.children[0].attribute("xl:href") == "a\\b.jpg");
  CHECK(root.children[0].attribute("ID") == "1");
  CHECK(root.children[0].attribute("missing").empty());
  CHECK(root.child("t")->text == "one & two");
  CHECK(root.children[2].text == "<raw>");
  CHECK(root.child("none") == nullptr);
  CHECK_THROWS_AS(xml::readElementTree("<r><a/><a/><a/></r>", "many.xml", 3), Error);
  CHECK_THROWS_AS(xml::readElementTree("<!DOCTYPE a [<!ENTITY e \"x\">]><a>&e;</a>", "dtd.xml", 10), Error);
}

TEST_CASE("a schema is parsed once but read again when its file changes") {
  const fs::path dir = fs::temp_directory_path() / ("surrogate-schema-" + std::to_string(::getpid()));
  fs::create_directories(dir);
  const fs::path xsd = dir / "s.xsd";
  auto writeSchema = [&](const std::string& element) {
    std::ofstream(xsd) << "<xs:schema xmlns:xs=\"http://www.w3.org/2001/XMLSchema\"><xs:element name=\"" << element
                       << "\"/></xs:schema>";
  };
  writeSchema("a");
  for (int i = 0; i < 3; ++i) xml::validateAgainstSchema("<a/>", "doc.xml", xsd);  // the same schema each time
  CHECK_THROWS_AS(xml::validateAgainstSchema("<ab/>", "doc.xml", xsd), Error);
  writeSchema("ab");  // another size: the file changed, and its new rules apply
  xml::validateAgainstSchema("<ab/>", "doc.xml", xsd);
  CHECK_THROWS_AS(xml::validateAgainstSchema("<a/>", "doc.xml", xsd), Error);
  fs::remove(xsd);
  CHECK_THROWS_AS(xml::validateAgainstSchema("<ab/>", "doc.xml", xsd), Error);  // gone: not served from memory
  fs::remove_all(dir);
}
