// base64 (core/base64.h, OpenSSL's encoder) against RFC 4648's vectors and a plain encoder
// written here from the RFC, on every length and byte value.
#include <catch2/catch.hpp>

#include <cstdint>
#include <string>

#include "core/base64.h"

using namespace surrogate;

namespace {
// RFC 4648 section 4, bit by bit: 6 bits at a time, '=' for what the last group lacks.
std::string referenceBase64(const std::string& bytes) {
  const char* alphabet = "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
  std::string out;
  for (std::size_t i = 0; i < bytes.size(); i += 3) {
    const std::size_t n = std::min<std::size_t>(3, bytes.size() - i);
    std::uint32_t group = 0;
    for (std::size_t k = 0; k < 3; ++k)
      group = group << 8 | (k < n ? static_cast<unsigned char>(bytes[i + k]) : 0u);
    for (std::size_t k = 0; k < 4; ++k) out += k <= n ? alphabet[(group >> (18 - 6 * k)) & 63] : '=';
  }
  return out;
}
}  // namespace

TEST_CASE("base64 matches the RFC 4648 test vectors") {
  CHECK(base64("") == "");
  CHECK(base64("f") == "Zg==");
  CHECK(base64("fo") == "Zm8=");
  CHECK(base64("foo") == "Zm9v");
  CHECK(base64("foob") == "Zm9vYg==");
  CHECK(base64("fooba") == "Zm9vYmE=");
  CHECK(base64("foobar") == "Zm9vYmFy");
  CHECK(base64(std::string("\xff\x00\x10", 3)) == "/wAQ");
}

TEST_CASE("base64 agrees with the RFC's encoding on every length and byte value, and appends") {
  std::string bytes;
  for (int i = 0; i < 1000; ++i) bytes += static_cast<char>((i * 151 + 7) % 256);
  for (std::size_t n = 0; n <= bytes.size(); n += (n < 20 ? 1 : 97)) {
    const std::string part = bytes.substr(0, n);
    INFO(n);
    REQUIRE(base64(part) == referenceBase64(part));
  }
  std::string out = "prefix:";
  appendBase64(out, bytes.data(), 5);
  appendBase64(out, bytes.data() + 5, 6);
  CHECK(out == "prefix:" + referenceBase64(bytes.substr(0, 5)) + referenceBase64(bytes.substr(5, 6)));
}
