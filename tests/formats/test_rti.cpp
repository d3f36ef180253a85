#include <catch2/catch.hpp>

#include "core/error.h"
#include "formats/rti_hsh.h"
#include "fuzz_support.h"

using namespace surrogate;
using namespace surrogate::formats;

namespace {
HshFile makeHsh(int terms, int w, int h) {
  HshFile f;
  f.width = w;
  f.height = h;
  f.terms = terms;
  for (int k = 0; k < terms; ++k) {
    f.scale.push_back(0.1f * (k + 1));
    f.bias.push_back(-0.05f * k);
  }
  f.coefficients.resize(f.texels() * 3 * terms);
  for (std::size_t i = 0; i < f.coefficients.size(); ++i)
    f.coefficients[i] = static_cast<std::uint8_t>(i * 29 + 3);
  return f;
}

HshFile parse(const std::string& s, RtiReadReport* report = nullptr) {
  return parseRti(reinterpret_cast<const std::uint8_t*>(s.data()), s.size(), "t.rti", report);
}

std::string parseError(const std::string& s) {
  try {
    parse(s);
  } catch (const Error& e) {
    CHECK(e.file() == "t.rti");
    return e.message();
  }
  FAIL("no error");
  return "";
}
}  // namespace

TEST_CASE("rti: 4-, 9- and 16-term files round trip bit-exactly") {
  for (int terms : {4, 9, 16}) {
    const HshFile f = makeHsh(terms, 3, 2);
    const std::string bytes = serializeRti(f);
    const HshFile g = parse(bytes);
    CHECK(g == f);
    CHECK(serializeRti(g) == bytes);
  }
}

TEST_CASE("rti: header, little-endian float tables and top-down texel order are exact") {
  HshFile f = makeHsh(4, 2, 2);
  f.scale = {1.0f, 2.0f, 0.5f, -1.0f};
  f.bias = {0.0f, 0.25f, 0, 0};
  std::fill(f.coefficients.begin(), f.coefficients.end(), 0);
  f.coefficients[((0 * 2 + 1) * 3 + 2) * 4 + 3] = 201;  // top row, x = 1, blue, term 3
  const std::string b = serializeRti(f);
  const std::string header = "#HSH1.2\n3\n2 2 3\n4 2 1\n";
  REQUIRE(b.substr(0, header.size()) == header);
  const std::string le = b.substr(header.size(), 8);
  CHECK(le == std::string("\x00\x00\x80\x3F\x00\x00\x00\x40", 8));  // 1.0f, 2.0f
  CHECK(b.substr(header.size() + 20, 4) == std::string("\x00\x00\x80\x3E", 4));  // bias 0.25f
  const std::size_t o = header.size() + 32;
  CHECK(b.size() == o + 2 * 2 * 3 * 4);
  // First stored texel row is the TOP image row: texel (1, 0) is stored second.
  CHECK(static_cast<unsigned char>(b[o + 12 + 2 * 4 + 3]) == 201);
  CHECK(f.coefficient(1, 0, 2, 3) == Approx(201 / 255.0 * -1.0));
}

TEST_CASE("rti: reader skips comments, accepts order codes, reports trailing bytes") {
  std::string s = "#HSH1.2\n# made elsewhere\n3\n1 1 3\n1 2 1\n";
  for (int i = 0; i < 8; ++i) s += std::string("\x00\x00\x80\x3F", 4);
  s += std::string(12, '\x07') + "zz";
  RtiReadReport report;
  const HshFile f = parse(s, &report);
  CHECK(f.terms == 4);
  CHECK(report.comments.size() == 2);
  CHECK(report.trailingBytes == 2);
  CHECK(f.coefficient(0, 0, 2, 3) == Approx(7 / 255.0 + 1));
}

TEST_CASE("rti: reader rejects other RTI types, channels, terms, sizes and non-finite tables") {
  CHECK_THAT(parseError("PTM_1.2\n"), Catch::Contains("not an RTI file"));
  CHECK_THAT(parseError("#HSH1.2\n1\n1 1 3\n9 2 1\n"), Catch::Contains("type 3"));
  CHECK_THAT(parseError("#HSH1.2\n3\n1 1 4\n9 2 1\n"), Catch::Contains("channels"));
  CHECK_THAT(parseError("#HSH1.2\n3\n1 1\n9 2 1\n"), Catch::Contains("size line"));
  CHECK_THAT(parseError("#HSH1.2\n3\n1 1 3\n7 2 1\n"), Catch::Contains("4, 9 or 16"));
  CHECK_THAT(parseError("#HSH1.2\n3\n0 1 3\n9 2 1\n"), Catch::Contains("out of range"));
  CHECK_THAT(parseError("#HSH1.2\n3\n65536 65536 3\n9 2 1\n"), Catch::Contains("out of range"));
  CHECK_THAT(parseError("#HSH1.2\n3\n40000 40000 3\n16 2 1\n"), Catch::Contains("truncated"));
  std::string nan = "#HSH1.2\n3\n1 1 3\n4 2 1\n" + std::string("\x00\x00\xC0\x7F", 4) +
                    std::string(28 + 12, '\0');
  CHECK_THAT(parseError(nan), Catch::Contains("finite"));
}

TEST_CASE("rti: a basis type other than 2 or an element size other than 1 is refused, naming the file") {
  // Every HSH writer writes "<terms> 2 1"; another declaration is a layout this reader would
  // misread (such files once rendered as if they were "2 1").
  std::string tables;
  for (int i = 0; i < 8; ++i) tables += std::string("\x00\x00\x80\x3F", 4);
  const std::string payload = tables + std::string(12, '\x07');
  CHECK_NOTHROW(parse("#HSH1.2\n3\n1 1 3\n4 2 1\n" + payload));
  CHECK_THAT(parseError("#HSH1.2\n3\n1 1 3\n4 99 1\n" + payload), Catch::Contains("basis type is 99"));
  CHECK_THAT(parseError("#HSH1.2\n3\n1 1 3\n4 0 1\n" + payload), Catch::Contains("basis type is 0"));
  CHECK_THAT(parseError("#HSH1.2\n3\n1 1 3\n4 2 0\n" + payload), Catch::Contains("element size is 0"));
  CHECK_THAT(parseError("#HSH1.2\n3\n1 1 3\n4 2 4\n" + payload), Catch::Contains("element size is 4"));
  CHECK_THAT(parseError("#HSH1.2\n3\n1 1 3\n4 2 -1\n" + payload), Catch::Contains("element size"));
  CHECK_THAT(parseError("#HSH1.2\n3\n1 1 3\n4 2 x\n" + payload), Catch::Contains("element size"));
}

TEST_CASE("rti: every prefix is rejected and mutations parse or throw Error") {
  for (int terms : {4, 9}) {
    const std::string bytes = serializeRti(makeHsh(terms, 3, 2));
    for (std::size_t n = 0; n < bytes.size(); ++n) CHECK_THROWS_AS(parse(bytes.substr(0, n)), Error);
    auto parser = [](const std::uint8_t* d, std::size_t n) {
      const HshFile f = parseRti(d, n, "f.rti");
      validateHsh(f, "f.rti");
    };
    test::fuzz(parser, bytes, 30 + 8 * terms, 3000, 100 + terms);
  }
}
