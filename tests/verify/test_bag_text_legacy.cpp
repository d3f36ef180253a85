// The BagIt text formats of bags other tools made: tag files in other encodings, md5 and sha1,
// fetch.txt (RFC 8493 sections 2.1.1, 2.2.3, 2.4).
#include <catch2/catch.hpp>

#include "archive/bag_text.h"
#include "generic_bag.h"

using namespace surrogate::archive;

TEST_CASE("bagit.txt may name UTF-16 or ISO-8859-1, not an encoding iconv does not know",
          "[verify][bagit]") {
  for (const char* encoding : {"UTF-8", "utf-8", "UTF-16", "ISO-8859-1", "UTF-16LE"}) {
    const Declaration d = parseDeclaration(std::string("BagIt-Version: 0.97\nTag-File-Character-Encoding: ") +
                                           encoding + "\n");
    INFO(encoding);
    CHECK(d.problems.empty());
    CHECK(d.encoding == encoding);
  }
  CHECK_FALSE(parseDeclaration("BagIt-Version: 1.0\nTag-File-Character-Encoding: KLINGON-8\n").problems.empty());
  CHECK_FALSE(parseDeclaration("BagIt-Version: 1.0\nTag-File-Character-Encoding: ../../x\n").problems.empty());
  CHECK_FALSE(tagEncodingSupported(""));
  CHECK_FALSE(tagEncodingSupported(std::string(200, 'A')));
}

TEST_CASE("decodeTagText reads UTF-16 with either byte-order mark and ISO-8859-1 into UTF-8",
          "[verify][bagit]") {
  const std::string text = "Contact-Name: Jos\xC3\xA9 M\xC3\xBCller\nExternal-Description: \xE2\x82\xAC 5\n";
  std::string why;
  CHECK(decodeTagText(verify_test::encodeAs(text, "UTF-16"), "UTF-16", &why) == text);
  // A little-endian file with its BOM, as Windows tools write it.
  const std::string le = "\xFF\xFE" + verify_test::encodeAs(text, "UTF-16LE");
  CHECK(decodeTagText(le, "UTF-16", &why) == text);
  const std::string latin = "Contact-Name: Jos\xC3\xA9 M\xC3\xBCller\n";
  CHECK(decodeTagText(verify_test::encodeAs(latin, "ISO-8859-1"), "ISO-8859-1", &why) == latin);
  // UTF-8 is returned as it is (its own checks, such as no BOM, still apply).
  CHECK(decodeTagText("\xEF\xBB\xBFx", "UTF-8", &why) == std::string("\xEF\xBB\xBFx"));

  CHECK_FALSE(decodeTagText(std::string("\xFF\xFE" "a", 3), "UTF-16", &why).has_value());
  CHECK_THAT(why, Catch::Matchers::Contains("middle of a character"));
  CHECK_FALSE(decodeTagText("x", "KLINGON-8", &why).has_value());
}

TEST_CASE("md5 and sha1 are legacy algorithms with their digest lengths", "[verify][bagit]") {
  CHECK(digestHexLength("md5") == 32);
  CHECK(digestHexLength("sha1") == 40);
  CHECK(isLegacyAlgorithm("md5"));
  CHECK(isLegacyAlgorithm("sha1"));
  CHECK_FALSE(isLegacyAlgorithm("sha256"));
  const Manifest m = parseManifest("d41d8cd98f00b204e9800998ecf8427e  data/empty file.txt\n", "md5", 32);
  REQUIRE(m.entries.size() == 1);
  CHECK(m.entries[0].path == "data/empty file.txt");
}

TEST_CASE("parseFetch: url, length or -, and the rest of the line as the path", "[verify][bagit]") {
  const Fetch f = parseFetch("http://example.org/a 12 data/test 1.txt\n"
                             "https://example.org/b\t-\tdata/100%25 sure.txt\r\n"
                             "\n"
                             "ftp://example.org/c   7   data/  leading spaces kept.txt\n");
  INFO(f.problems.size());
  CHECK(f.problems.empty());
  REQUIRE(f.entries.size() == 3);
  CHECK(f.entries[0].url == "http://example.org/a");
  CHECK(f.entries[0].length == std::optional<std::uint64_t>(12));
  CHECK(f.entries[0].path == "data/test 1.txt");
  CHECK_FALSE(f.entries[1].length.has_value());
  CHECK(f.entries[1].path == "data/100% sure.txt");
  CHECK(f.entries[1].line == 2);
  CHECK(f.entries[2].path == "data/  leading spaces kept.txt");

  for (const char* bad : {"http://example.org/a 12\n", "http://example.org/a twelve data/x\n",
                          "no-scheme 1 data/x\n", "http://example.org/a 1 ../x\n",
                          "http://example.org/a 99999999999999999999 data/x\n",
                          // decoded, but a line break in a name is refused, as in manifests
                          "http://example.org/a 1 data/a%0Ab\n"}) {
    INFO(bad);
    const Fetch b = parseFetch(bad);
    CHECK(b.entries.empty());
    CHECK(b.problems.size() == 1);
  }
}
