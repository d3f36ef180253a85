#include <catch2/catch.hpp>

#include "archive/bag_text.h"
#include "core/digest.h"

using namespace surrogate::archive;
using surrogate::DigestAlgorithm;
using surrogate::MultiDigest;

TEST_CASE("safeBagPath accepts relative paths and strips a leading ./", "[verify][paths]") {
  std::string why;
  CHECK(safeBagPath("data/original-captures/IMG_0001.dng", &why) == "data/original-captures/IMG_0001.dng");
  CHECK(safeBagPath("./data/a b.txt", &why) == "data/a b.txt");
  CHECK(safeBagPath("data/caf\xC3\xA9.jpg", &why) == "data/caf\xC3\xA9.jpg");
}

TEST_CASE("safeBagPath refuses every path that could leave the bag", "[verify][paths]") {
  for (const char* bad : {"../etc/passwd", "data/../../x", "/etc/passwd", "C:/x", "C:\\x",
                          "\\\\server\\share", "~root/.ssh", "data//x", "data/./x", "", ".",
                          "data/a\nb", "data/\x7f", "data/\xC3(", "data/\xED\xA0\x80"}) {
    std::string why;
    CHECK_FALSE(safeBagPath(bad, &why).has_value());
    CHECK_FALSE(why.empty());
  }
  std::string why;
  CHECK_FALSE(safeBagPath(std::string(2000, 'a'), &why).has_value());
}

TEST_CASE("percentDecode decodes only %0D, %0A and %25, in either case", "[verify][paths]") {
  CHECK(percentDecode("data/100%25.txt") == "data/100%.txt");
  CHECK(percentDecode("a%0ab%0D") == "a\nb\r");
  CHECK(percentDecode("data/%2e%2e/x") == "data/%2e%2e/x");  // never produces ".." or "/"
  CHECK(percentDecode("trailing%2") == "trailing%2");
}

TEST_CASE("bagit.txt must declare version 1.0 and UTF-8 in exactly two lines", "[verify][bagit]") {
  CHECK(parseDeclaration("BagIt-Version: 1.0\nTag-File-Character-Encoding: UTF-8\n").problems.empty());
  CHECK(parseDeclaration("BagIt-Version: 1.0\r\nTag-File-Character-Encoding: UTF-8\r\n").problems.empty());
  CHECK_FALSE(parseDeclaration("BagIt-Version : 1.0\nTag-File-Character-Encoding: UTF-8\n").problems.empty());
  CHECK_FALSE(parseDeclaration("\xEF\xBB\xBF" "BagIt-Version: 1.0\nTag-File-Character-Encoding: UTF-8\n").problems.empty());
  CHECK_FALSE(parseDeclaration("BagIt-Version: 2.0\nTag-File-Character-Encoding: UTF-8\n").problems.empty());
  CHECK_FALSE(parseDeclaration("BagIt-Version: 1.0\n").problems.empty());
  CHECK_FALSE(parseDeclaration("BagIt-Version: 1.0\nTag-File-Character-Encoding: NO-SUCH-CODE\n").problems.empty());
}

TEST_CASE("bag-info.txt labels, continuation lines and non-repeatable labels", "[verify][bagit]") {
  const BagInfo info = parseBagInfo("Source-Organization: Museum\nExternal-Description: a long\n"
                                    "  description\nPayload-Oxum: 10.2\n");
  CHECK(info.problems.empty());
  CHECK(info.values("external-description") == std::vector<std::string>{"a long description"});
  // Repeated reserved labels and whitespace before the colon: what RFC 8493 advises against
  // without forbidding (the verifier warns in another tool's bag, fails a Surrogate package).
  const BagInfo repeated = parseBagInfo("Payload-Oxum: 1.1\nPayload-Oxum: 2.2\nBagging-Date: 2016-02-26\n"
                                        "bagging-date: 2016-03-10\nContact-Name: A\nContact-Name: B\n");
  CHECK(repeated.problems.empty());
  CHECK(repeated.departures.size() == 2);  // Contact-Name may repeat
  const BagInfo spaced = parseBagInfo("Test-Tag : 3\nTest-Tag    :   5\n");
  CHECK(spaced.problems.empty());
  CHECK(spaced.departures.size() == 2);
  CHECK(spaced.values("test-tag") == std::vector<std::string>{"3", "5"});
  CHECK_FALSE(parseBagInfo(" orphan continuation\n").problems.empty());
  CHECK_FALSE(parseBagInfo("no colon here\n").problems.empty());
}

TEST_CASE("Payload-Oxum parses octets.streams and nothing else", "[verify][bagit]") {
  CHECK(parseOxum("1234.5") == std::make_pair<std::uint64_t, std::uint64_t>(1234, 5));
  CHECK_FALSE(parseOxum("1234").has_value());
  CHECK_FALSE(parseOxum("12a.5").has_value());
  CHECK_FALSE(parseOxum(".5").has_value());
  CHECK_FALSE(parseOxum("99999999999999999999999.1").has_value());
}

TEST_CASE("manifest lines: checksum, whitespace, escaped path", "[verify][bagit]") {
  const std::string h(64, 'a');
  const Manifest m = parseManifest(h + "  data/a%25b.txt\n" + h + "\tdata/c d.txt\r\n", "sha256", 64);
  REQUIRE(m.problems.empty());
  REQUIRE(m.entries.size() == 2);
  CHECK(m.entries[0].path == "data/a%b.txt");
  CHECK(m.entries[1].path == "data/c d.txt");
}

TEST_CASE("manifest problems: bad checksum, unsafe path, duplicates", "[verify][bagit]") {
  const std::string h(64, 'b');
  CHECK(parseManifest("xyz  data/a\n", "sha256", 64).problems.size() == 1);
  CHECK(parseManifest(std::string(63, 'a') + "  data/a\n", "sha256", 64).problems.size() == 1);
  CHECK(parseManifest(h + "  ../../etc/passwd\n", "sha256", 64).problems.size() == 1);
  CHECK(parseManifest(h + "  /etc/passwd\n", "sha256", 64).problems.size() == 1);
  CHECK(parseManifest(h + "  data/a\n" + std::string(64, 'c') + "  data/a\n", "sha256", 64).problems.size() == 1);
  CHECK(parseManifest(h + "\n", "sha256", 64).problems.size() == 1);
  // The same path with the same checksum again: kept once, a repeat (the verifier refuses it
  // in BagIt 1.0 and warns in 0.97).
  const Manifest twice = parseManifest(h + "  data/a\n" + h + "  ./data/a\n", "sha256", 64);
  CHECK(twice.problems.empty());
  CHECK(twice.entries.size() == 1);
  CHECK(twice.repeats.size() == 1);
}

TEST_CASE("manifest lines written by md5sum: the binary-mode '*' is not part of the path",
          "[verify][bagit]") {
  const std::string h(32, 'd');
  const Manifest m = parseManifest(h + " *data/hello.txt\n" + h + "  *data/star.txt\n", "md5", 32);
  CHECK(m.problems.empty());
  REQUIRE(m.entries.size() == 2);
  CHECK(m.entries[0].path == "data/hello.txt");
  CHECK(m.departures.size() == 1);
  CHECK(m.entries[1].path == "*data/star.txt");  // two spaces: the '*' belongs to the name
}

TEST_CASE("manifest algorithms: any digest OpenSSL offers, by its BagIt name", "[verify][bagit]") {
  CHECK(digestHexLength("sha224") == 56);
  CHECK(digestHexLength("sha384") == 96);
  CHECK(digestHexLength("sha3_256") == 64);  // bagit-python's spelling
  CHECK(digestHexLength("sha3-512") == 128);
  CHECK(digestHexLength("blake2b") == 128);
  CHECK(digestHexLength("shake128") == 0);  // no fixed length
  CHECK(digestHexLength("null") == 0);
  CHECK(digestHexLength("SHA224") == 0);     // BagIt names are lower case
  CHECK(digestHexLength("../sha256") == 0);
  MultiDigest d(std::vector<std::string>{"sha224", "sha256"});
  d.update("abc", 3);
  CHECK(d.hex("sha224") == "23097d223405d8228642a477bda255b32aadbce4bda0b3f7e36c9da7");
  CHECK(d.hex(DigestAlgorithm::Sha256) ==
        "ba7816bf8f01cfea414140de5dae2223b00361a396177a9cb410ff61f20015ad");
}

TEST_CASE("manifest names give kind and algorithm", "[verify][bagit]") {
  CHECK(manifestName("manifest-sha256.txt")->second == "sha256");
  CHECK(manifestName("tagmanifest-sha512.txt")->first == "tagmanifest");
  CHECK_FALSE(manifestName("data/manifest-sha256.txt").has_value());
  CHECK_FALSE(manifestName("bag-info.txt").has_value());
  CHECK(digestHexLength("crc32") == 0);
}

