#include <catch2/catch.hpp>

#include <cmath>
#include <cstdio>
#include <limits>
#include <optional>
#include <string>
#include <vector>

#include "core/error.h"
#include "core/text.h"

using namespace surrogate;

// The expected texts are written out by hand, not produced by another formatter: a change of
// digits or notation shows here.
TEST_CASE("formatNumber writes the shortest text that reads back as the same double", "[core][text]") {
  CHECK(formatNumber(0.1) == "0.1");
  CHECK(formatNumber(0.8) == "0.8");
  CHECK(formatNumber(0.3) == "0.3");
  CHECK(formatNumber(0.1 + 0.2) == "0.30000000000000004");  // not 0.3: a different double
  CHECK(formatNumber(1.0 / 3.0) == "0.3333333333333333");
  CHECK(formatNumber(2.0 / 3.0) == "0.6666666666666666");
  CHECK(formatNumber(-1.5) == "-1.5");
  CHECK(formatNumber(45.000000000000007) == "45.00000000000001");
}

TEST_CASE("formatNumber writes whole numbers without a point or an exponent", "[core][text]") {
  CHECK(formatNumber(0.0) == "0");
  CHECK(formatNumber(1.0) == "1");
  CHECK(formatNumber(-7.0) == "-7");
  CHECK(formatNumber(100.0) == "100");
  CHECK(formatNumber(1000000.0) == "1000000");
  CHECK(formatNumber(9007199254740991.0) == "9.007199254740991e+15");  // 2^53-1: above 1e15
  CHECK(formatNumber(123456789012345.0) == "123456789012345");
  CHECK(formatNumber(1e15) == "1e+15");
}

TEST_CASE("formatNumber keeps the sign of negative zero", "[core][text]") {
  // "-0" reads back as -0.0, so a recorded -0 is the same double again (atan2 tells them apart).
  CHECK(formatNumber(-0.0) == "-0");
}

TEST_CASE("formatNumber uses an exponent only for very small and very large magnitudes", "[core][text]") {
  CHECK(formatNumber(0.000001) == "0.000001");
  CHECK(formatNumber(0.000125) == "0.000125");
  CHECK(formatNumber(0.0000001) == "1e-07");
  CHECK(formatNumber(1e-300) == "1e-300");
  CHECK(formatNumber(-2.5e-10) == "-2.5e-10");
  CHECK(formatNumber(1e21) == "1e+21");
  CHECK(formatNumber(1.5e300) == "1.5e+300");
  CHECK(formatNumber(std::numeric_limits<double>::max()) == "1.7976931348623157e+308");
}

TEST_CASE("formatNumber writes denormals with their shortest digits", "[core][text]") {
  CHECK(formatNumber(std::numeric_limits<double>::denorm_min()) == "5e-324");
  CHECK(formatNumber(-std::numeric_limits<double>::denorm_min()) == "-5e-324");
  CHECK(formatNumber(2.2250738585072009e-308) == "2.225073858507201e-308");  // largest denormal
  CHECK(formatNumber(std::numeric_limits<double>::min()) == "2.2250738585072014e-308");
}

TEST_CASE("formatNumber text reads back as the identical double", "[core][text]") {
  for (double v : {0.1, 0.8, 1e-300, 1e21, 5e-324, 0.30000000000000004, 123.456, -98.7654321e-5,
                   std::nextafter(1.0, 2.0), std::nextafter(0.8, 0.0)}) {
    const std::string text = formatNumber(v);
    INFO(text);
    CHECK(std::strtod(text.c_str(), nullptr) == v);
  }
  CHECK(formatNumber(std::nextafter(1.0, 2.0)) == "1.0000000000000002");
  CHECK(formatNumber(std::nextafter(0.8, 0.0)) == "0.7999999999999999");
}

TEST_CASE("formatNumber refuses NaN and infinities", "[core][text]") {
  // No record holds them; one reaching the writer is a bug, not a value to write as "nan".
  for (double v : {std::numeric_limits<double>::quiet_NaN(), std::numeric_limits<double>::infinity(),
                   -std::numeric_limits<double>::infinity()}) {
    try {
      formatNumber(v);
      FAIL("no error for a non-finite number");
    } catch (const Error& e) {
      CHECK(e.kind() == ErrorKind::Internal);
    }
  }
}

TEST_CASE("escapedText keeps clean text and writes bad bytes and control characters as hex escapes") {
  CHECK(escapedText("Canon EOS 5D Mark IV") == "Canon EOS 5D Mark IV");
  CHECK(escapedText("Ca\xC3\xB1on \xE2\x80\x94 \xF0\x9F\x93\xB7") == "Ca\xC3\xB1on \xE2\x80\x94 \xF0\x9F\x93\xB7");
  CHECK(escapedText("Can\xE9n") == "Can\\xE9n");              // Latin-1, not UTF-8
  CHECK(escapedText("EOS\x01" "5D") == "EOS\\x015D");         // C0 control
  CHECK(escapedText(std::string("a\0b", 3)) == "a\\x00b");    // NUL
  CHECK(escapedText("a\x7F" "b") == "a\\x7Fb");               // DEL
  CHECK(escapedText("a\xC2\x9B" "b") == "a\\xC2\\x9Bb");      // C1 CSI, which terminals obey
  CHECK(escapedText("a\xEF\xBF\xBE") == "a\\xEF\\xBF\\xBE");  // U+FFFE, not an XML character
  CHECK(escapedText("\xC0\xAF") == "\\xC0\\xAF");             // overlong
  CHECK(escapedText("\xE2\x82") == "\\xE2\\x82");             // cut short
  CHECK(escapedText("one\ttwo\r\n") == "one\\x09two\\x0D\\x0A");
  CHECK(escapedText("one\ttwo\r\n", true) == "one\ttwo\r\n");
  CHECK_FALSE(needsEscaping("Nikon D850"));
  CHECK(needsEscaping("Nikon\nD850"));
  CHECK_FALSE(needsEscaping("Nikon\nD850", true));
  CHECK(hexBytes("Can\xE9n") == "43616ee96e");
  CHECK(hexBytes("") == "");
}

// The optimal string alignment distance, against the textbook values: kitten/sitting 3 (the
// classic Levenshtein example), and ca/abc 3, the example that tells this distance from the
// unrestricted Damerau-Levenshtein one (2): a swapped pair is not edited again.
TEST_CASE("editDistance counts insertions, deletions, substitutions and swaps of neighbours", "[core][text]") {
  CHECK(editDistance("kitten", "sitting") == 3);
  CHECK(editDistance("ca", "abc") == 3);
  CHECK(editDistance("", "abc") == 3);
  CHECK(editDistance("abc", "") == 3);
  CHECK(editDistance("title", "title") == 0);
  CHECK(editDistance("titel", "title") == 1);   // one swap
  CHECK(editDistance("verfy", "verify") == 1);  // one insertion
  CHECK(editDistance("verify", "verfy") == 1);  // symmetric
  CHECK(editDistance("pakc", "pack") == 1);
  CHECK(editDistance("IMG_003", "IMG_0003") == 1);
}

TEST_CASE("nearestName suggests only a close name or the one name a prefix begins", "[core][text]") {
  const std::vector<std::string> commands = {"run", "pack", "lights", "fit", "render", "publish",
                                             "info", "report", "verify", "audit"};
  CHECK(nearestName("verfy", commands) == std::optional<std::string>("verify"));
  CHECK(nearestName("pakc", commands) == std::optional<std::string>("pack"));
  CHECK(nearestName("reprot", commands) == std::optional<std::string>("report"));
  // Too far, or too short for a distance to mean anything.
  CHECK_FALSE(nearestName("frobnicate", commands));
  CHECK_FALSE(nearestName("x", commands));
  CHECK(nearestName("rn", commands) == std::optional<std::string>("run"));  // 1 edit in two letters
  CHECK_FALSE(nearestName("xy", commands));  // 2 edits in two letters: too far
  CHECK_FALSE(nearestName("", commands));
  CHECK_FALSE(nearestName("run", commands));  // the name itself is no suggestion
  // Equally near to two: no guess.
  CHECK_FALSE(nearestName("cat", {"bat", "hat"}));
  // A prefix of exactly one name, however short; of two, none.
  CHECK(nearestName("reexec", {"reexecute", "threads"}) == std::optional<std::string>("reexecute"));
  CHECK(nearestName("pu", {"publish", "pack"}) == std::optional<std::string>("publish"));
  CHECK_FALSE(nearestName("p", {"publish", "pack"}));
  // Case matters: the caller compares file names without regard to case itself.
  CHECK_FALSE(nearestName("TITLE", {"title"}));
}

TEST_CASE("escapeHtml neutralises markup in element content and quoted attributes") {
  CHECK(escapeHtml("<b a=\"x\" b='y'>&</b>") == "&lt;b a=&quot;x&quot; b=&#39;y&#39;&gt;&amp;&lt;/b&gt;");
  CHECK(escapeHtml("Stela 12 \xc3\xa9") == "Stela 12 \xc3\xa9");  // UTF-8 passes through
}

TEST_CASE("shellWord gives one word that a POSIX shell reads back as the text") {
  CHECK(shellWord("stela12/IMG_0001.dng") == "stela12/IMG_0001.dng");
  CHECK(shellWord("--reset") == "--reset");  // an option's value stays a word of its own
  // Read back by /bin/sh itself, not by a second copy of the rule.
  for (const std::string text : {"Stela 12", "it's", "$HOME `id` \"q\"", "a;b|c&d", "", "*?[x]", "tab\there"}) {
    INFO(text);
    const std::string word = shellWord(text);
    FILE* sh = popen(("printf '%s' " + word).c_str(), "r");
    REQUIRE(sh);
    std::string read;
    char buffer[256];
    for (std::size_t n; (n = std::fread(buffer, 1, sizeof buffer, sh)) > 0;) read.append(buffer, n);
    CHECK(pclose(sh) == 0);
    CHECK(read == text);
  }
}
