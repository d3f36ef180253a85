#include <catch2/catch.hpp>

#include "core/image.h"

using namespace surrogate;

TEST_CASE("luminance of white is white and of pure green is its Rec.709 weight") {
  Image rgb(2, 1, 3);
  rgb.at(0, 0, 0) = rgb.at(0, 0, 1) = rgb.at(0, 0, 2) = 65535;
  rgb.at(1, 0, 1) = 65535;
  const Image y = luminance(rgb);
  REQUIRE(y.channels == 1);
  CHECK(y.at(0, 0) == 65535);
  CHECK(y.at(1, 0) == Approx(0.7152 * 65535).margin(1));
}

#include <vector>

#include "core/cpu_features.h"

TEST_CASE("8-bit luminance: every colour against the integer Rec. 709 weights, in both variants") {
  // All 2^24 colours: the reference is the formula (docs/hrti-math.md, "Spheres in the median
  // image"), on samples widened by 257.
  const std::size_t count = std::size_t(1) << 24;
  std::vector<std::uint8_t> rgb(3 * count);
  std::vector<std::uint16_t> expected(count);
  for (std::size_t c = 0; c < count; ++c) {
    const std::uint32_t r = c >> 16, g = (c >> 8) & 255, b = c & 255;
    rgb[3 * c] = static_cast<std::uint8_t>(r);
    rgb[3 * c + 1] = static_cast<std::uint8_t>(g);
    rgb[3 * c + 2] = static_cast<std::uint8_t>(b);
    expected[c] = static_cast<std::uint16_t>((13933 * 257 * r + 46871 * 257 * g + 4732 * 257 * b + 32768) / 65536);
  }
  std::vector<std::uint16_t> out(count);
  surrogate::detail::luminanceOfPixelsBaseline(rgb.data(), count, out.data());
  CHECK(out == expected);
  if (surrogate::cpuHasAvx2()) {
    std::fill(out.begin(), out.end(), 0);
    surrogate::detail::luminanceOfPixelsAvx2(rgb.data(), count, out.data());
    CHECK(out == expected);
  }
  std::fill(out.begin(), out.end(), 0);
  surrogate::luminanceOfPixels(rgb.data(), count, out.data());
  CHECK(out == expected);
}

TEST_CASE("8-bit luminance: every length and start, as the vector loop's blocks and tail divide them") {
  // Blocks of sixteen pixels and a tail: lengths 0 to 49 from each of the first 17 pixels of a
  // varied row, against the formula; the bytes after the last pixel are never read as pixels.
  std::vector<std::uint8_t> rgb(3 * 80);
  for (std::size_t k = 0; k < rgb.size(); ++k) rgb[k] = static_cast<std::uint8_t>((k * 97 + 13) ^ (k >> 3));
  for (std::size_t start = 0; start < 17; ++start)
    for (std::size_t count = 0; count < 50; ++count) {
      std::vector<std::uint16_t> out(count + 1, 0xBEEF), expected(count + 1, 0xBEEF);
      for (std::size_t i = 0; i < count; ++i) {
        const std::uint8_t* p = &rgb[3 * (start + i)];
        expected[i] = static_cast<std::uint16_t>((13933u * 257 * p[0] + 46871u * 257 * p[1] + 4732u * 257 * p[2] + 32768) / 65536);
      }
      surrogate::luminanceOfPixels(&rgb[3 * start], count, out.data());
      CHECK(out == expected);  // out[count] untouched
    }
}

#include "core/json.h"

TEST_CASE("JsonWriter separates members and escapes control characters") {
  JsonWriter j;
  j.beginObject().key("a").value(1).key("b").beginArray().value("x\"\n").value(true).endArray()
      .key("c").value(0.5).endObject();
  CHECK(j.str() == "{\"a\":1,\"b\":[\"x\\\"\\n\",true],\"c\":0.5}");
}
