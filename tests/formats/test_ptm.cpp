#include <catch2/catch.hpp>

#include <cstring>

#include "core/error.h"
#include "formats/ptm.h"
#include "fuzz_support.h"

using namespace surrogate;
using namespace surrogate::formats;

namespace {
PtmFile makePtm(PtmFile::Format format, int w, int h) {
  PtmFile p;
  p.format = format;
  p.width = w;
  p.height = h;
  p.scale = {0.5, 1.25, 0.0000001, 3, 0.123456789012345, 1e6};
  p.bias = {0, 12, 127, 255, 40, 7};
  const std::size_t texels = static_cast<std::size_t>(w) * h;
  p.coefficients.resize(texels * (format == PtmFile::Format::Lrgb ? 6 : 18));
  for (std::size_t i = 0; i < p.coefficients.size(); ++i)
    p.coefficients[i] = static_cast<std::uint8_t>(i * 37 + 11);
  if (format == PtmFile::Format::Lrgb) {
    p.rgb.resize(texels * 3);
    for (std::size_t i = 0; i < p.rgb.size(); ++i) p.rgb[i] = static_cast<std::uint8_t>(i * 13 + 5);
  }
  return p;
}

PtmFile parse(const std::string& s, PtmReadReport* report = nullptr) {
  return parsePtm(reinterpret_cast<const std::uint8_t*>(s.data()), s.size(), "t.ptm", report);
}

std::string parseError(const std::string& s) {
  try {
    parse(s);
  } catch (const Error& e) {
    CHECK(e.file() == "t.ptm");
    return e.message();
  }
  FAIL("no error");
  return "";
}

const std::string kHeader =
    "PTM_1.2\nPTM_FORMAT_LRGB\n2\n3\n0.5 1.25 0.0000001 3 0.123456789012345 1000000\n"
    "0 12 127 255 40 7\n";
}  // namespace

TEST_CASE("ptm: LRGB and RGB round trip bit-exactly") {
  for (auto format : {PtmFile::Format::Lrgb, PtmFile::Format::Rgb}) {
    const PtmFile p = makePtm(format, 5, 4);
    const std::string bytes = serializePtm(p);
    const PtmFile q = parse(bytes);
    CHECK(q == p);
    CHECK(serializePtm(q) == bytes);
  }
}

TEST_CASE("ptm: header is byte-exact: separate size lines, plain decimals, no trailing space") {
  const std::string bytes = serializePtm(makePtm(PtmFile::Format::Lrgb, 2, 3));
  REQUIRE(bytes.size() == kHeader.size() + 9 * 6);
  CHECK(bytes.substr(0, kHeader.size()) == kHeader);
  CHECK(bytes.find('e', 0) > kHeader.size());  // no exponent in the header
}

TEST_CASE("ptm: rows are stored bottom-up, LRGB is a 6-byte block then a 3-byte block") {
  PtmFile p = makePtm(PtmFile::Format::Lrgb, 2, 3);
  std::fill(p.coefficients.begin(), p.coefficients.end(), 0);
  std::fill(p.rgb.begin(), p.rgb.end(), 0);
  for (int x = 0; x < 2; ++x)
    for (int k = 0; k < 6; ++k) p.coefficients[(0 * 2 + x) * 6 + k] = 200;  // top row
  for (int k = 0; k < 6; ++k) p.coefficients[(2 * 2 + 1) * 6 + k] = static_cast<std::uint8_t>(k + 1);
  p.rgb[(2 * 2 + 1) * 3 + 2] = 99;  // bottom-right blue
  const std::string b = serializePtm(p);
  const std::size_t o = kHeader.size();
  // First stored texel row = bottom image row: texel (1, 2) is the 2nd stored texel.
  CHECK(static_cast<unsigned char>(b[o + 6 + 0]) == 1);
  CHECK(static_cast<unsigned char>(b[o + 6 + 5]) == 6);
  // Last stored row = top row.
  CHECK(static_cast<unsigned char>(b[o + 4 * 6]) == 200);
  CHECK(static_cast<unsigned char>(b[o + 5 * 6 + 5]) == 200);
  // Colour block starts after 6 * texels bytes, same bottom-up order.
  CHECK(static_cast<unsigned char>(b[o + 36 + 3 + 2]) == 99);
}

TEST_CASE("ptm: RGB stores three bottom-up blocks, red, green, blue") {
  PtmFile p = makePtm(PtmFile::Format::Rgb, 1, 2);
  std::fill(p.coefficients.begin(), p.coefficients.end(), 0);
  p.coefficients[((1 * 2 + 0) * 1 + 0) * 6 + 3] = 77;  // green, top row, a3
  const std::string b = serializePtm(p);
  const std::size_t o = b.size() - 36;
  // green block = bytes [12, 24); top row stored second -> offset 12 + 6 + 3
  CHECK(static_cast<unsigned char>(b[o + 12 + 6 + 3]) == 77);
  CHECK(p.coefficient(0, 0, 3, 1) == (77 - p.bias[3]) * p.scale[3]);
}

TEST_CASE("ptm: reader accepts PTM_1.1 LRGB, w h on one line, CRLF and extra spaces") {
  std::string s = "PTM_1.1\r\nPTM_FORMAT_LRGB\r\n1 2\r\n 1  1 1 1 1 1 \r\n0 0 0 0 0 0\r\n";
  for (int i = 0; i < 18; ++i) s += static_cast<char>(i);
  s += "xx";
  PtmReadReport report;
  const PtmFile p = parse(s, &report);
  CHECK(report.version == "PTM_1.1");
  CHECK(report.sizeOnOneLine);
  CHECK(report.trailingBytes == 2);
  // Stored texel 0 (bytes 0..8) is the bottom row (y = 1).
  CHECK(p.byte(0, 1, 0) == 0);
  CHECK(p.rgb[3 + 2] == 8);
  CHECK(p.byte(0, 0, 5) == 14);
  CHECK(p.rgb[0] == 15);
}

TEST_CASE("ptm: reader rejects bad magic, formats, dimensions and truncation") {
  const std::string body = "0.5 1 1 1 1 1\n0 0 0 0 0 0\n";
  CHECK_THAT(parseError("GIF89a"), Catch::Contains("not a PTM file"));
  CHECK_THAT(parseError("PTM_2.0\nPTM_FORMAT_LRGB\n1\n1\n" + body), Catch::Contains("version"));
  CHECK_THAT(parseError("PTM_1.2\nPTM_FORMAT_LUM\n1\n1\n" + body), Catch::Contains("not supported"));
  CHECK_THAT(parseError("PTM_1.2\nPTM_FORMAT_JPEG_LRGB\n1\n1\n" + body), Catch::Contains("compression parameter"));
  CHECK_THAT(parseError("PTM_1.2\nBANANA\n1\n1\n" + body), Catch::Contains("format"));
  CHECK_THAT(parseError("PTM_1.2\nPTM_FORMAT_LRGB\n70000\n1\n" + body), Catch::Contains("outside"));
  CHECK_THAT(parseError("PTM_1.2\nPTM_FORMAT_LRGB\n0\n1\n" + body), Catch::Contains("outside"));
  CHECK_THAT(parseError("PTM_1.2\nPTM_FORMAT_LRGB\n65536\n65536\n" + body), Catch::Contains("2^31"));
  CHECK_THAT(parseError("PTM_1.2\nPTM_FORMAT_LRGB\n99999999999999999999\n1\n" + body),
             Catch::Contains("not an integer"));
  CHECK_THAT(parseError("PTM_1.2\nPTM_FORMAT_LRGB\n1\n1\n1 1 1 1 1\n0 0 0 0 0 0\n"), Catch::Contains("6 scale"));
  CHECK_THAT(parseError("PTM_1.2\nPTM_FORMAT_LRGB\n1\n1\n1 1 1 1 1 inf\n0 0 0 0 0 0\n"), Catch::Contains("finite"));
  CHECK_THAT(parseError("PTM_1.2\nPTM_FORMAT_LRGB\n1\n1\n1 1 1 1 1 1\n0 0 0 0 0 256\n"), Catch::Contains("0..255"));
  CHECK_THAT(parseError("PTM_1.2\nPTM_FORMAT_LRGB\n40000\n40000\n" + body), Catch::Contains("truncated"));
}

TEST_CASE("ptm: every prefix of a valid file is rejected with an Error") {
  for (auto format : {PtmFile::Format::Lrgb, PtmFile::Format::Rgb}) {
    const std::string bytes = serializePtm(makePtm(format, 3, 2));
    for (std::size_t n = 0; n < bytes.size(); ++n) {
      const std::string prefix = bytes.substr(0, n);
      CHECK_THROWS_AS(parse(prefix), Error);
    }
  }
}

TEST_CASE("ptm: thousands of mutations parse into a valid object or throw Error") {
  for (auto format : {PtmFile::Format::Lrgb, PtmFile::Format::Rgb}) {
    const std::string bytes = serializePtm(makePtm(format, 3, 2));
    auto parser = [](const std::uint8_t* d, std::size_t n) {
      const PtmFile p = parsePtm(d, n, "f.ptm");
      validatePtm(p, "f.ptm");  // whatever parses is writable
    };
    test::fuzz(parser, bytes, 90, 3000, format == PtmFile::Format::Lrgb ? 1 : 2);
  }
}

TEST_CASE("ptm: the writer refuses objects it cannot write correctly") {
  PtmFile p = makePtm(PtmFile::Format::Lrgb, 2, 2);
  p.rgb.pop_back();
  CHECK_THROWS_AS(serializePtm(p), Error);
  p = makePtm(PtmFile::Format::Lrgb, 2, 2);
  p.bias[0] = 300;
  CHECK_THROWS_AS(serializePtm(p), Error);
  p = makePtm(PtmFile::Format::Lrgb, 2, 2);
  p.scale[0] = std::nan("");
  CHECK_THROWS_AS(serializePtm(p), Error);
}
