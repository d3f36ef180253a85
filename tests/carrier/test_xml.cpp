#include <catch2/catch.hpp>

#include "carrier/xml.h"
#include "core/error.h"

using namespace surrogate;

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
