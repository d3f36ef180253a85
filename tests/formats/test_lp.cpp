#include <catch2/catch.hpp>

#include <cmath>
#include <filesystem>

#include "core/atomic_file.h"
#include "core/error.h"
#include "formats/lp.h"
#include "fuzz_support.h"

using namespace surrogate;
using namespace surrogate::formats;
namespace fs = std::filesystem;

namespace {
std::string errorOf(const std::string& text) {
  try {
    parseLp(text, "lights.lp");
  } catch (const Error& e) {
    CHECK(e.kind() == ErrorKind::Input);
    CHECK(e.file() == "lights.lp");
    return e.message();
  }
  FAIL("no error for: " << text);
  return "";
}
}  // namespace

TEST_CASE("lp: reads names with spaces, CRLF line ends and normalises directions") {
  const auto l = parseLp("\xEF\xBB\xBF" "2\r\nC:\\caps\\my photo 1.jpg 0 0 2\r\n\r\nb.jpg\t3 0 4\r\n",
                         "x.lp");
  REQUIRE(l.size() == 2);
  CHECK(l[0].filename == "C:\\caps\\my photo 1.jpg");
  CHECK(l[0].z == 1.0);
  CHECK(l[1].filename == "b.jpg");
  CHECK(l[1].x == Approx(0.6));
  CHECK(l[1].z == Approx(0.8));
}

TEST_CASE("lp: errors name the file and the line") {
  CHECK_THAT(errorOf("0\n"), Catch::Contains("line 1") && Catch::Contains("between 1 and 1000"));
  CHECK_THAT(errorOf("1001\n"), Catch::Contains("between 1 and 1000"));
  CHECK_THAT(errorOf("two\na 0 0 1\n"), Catch::Contains("line 1"));
  CHECK_THAT(errorOf("2\na 0 0 1\n"), Catch::Contains("announces 2") && Catch::Contains("lists 1"));
  CHECK_THAT(errorOf("1\na 0 0 1\nb 0 0 1\n"), Catch::Contains("line 3"));
  CHECK_THAT(errorOf("2\na 0 0 1\nb 0 0.00001 0\n"), Catch::Contains("line 3") &&
                                                        Catch::Contains("zero length"));
  CHECK_THAT(errorOf("1\na 0 x 1\n"), Catch::Contains("line 2") && Catch::Contains("not a number"));
  CHECK_THAT(errorOf("1\na 0 1\n"), Catch::Contains("line 2"));
  CHECK_THAT(errorOf(""), Catch::Contains("empty"));
  CHECK_THAT(errorOf("1\na nan 0 1\n"), Catch::Contains("not a number"));
}

TEST_CASE("lp: write then read round trips, and the text is exactly the spec's layout") {
  const fs::path dir = fs::temp_directory_path() / "surrogate-test-lp";
  fs::remove_all(dir);
  fs::create_directories(dir);
  std::vector<LightEntry> in = {{"IMG 0001.JPG", 0.6, 0.0, 0.8}, {"b.jpg", -0.5, 0.5, std::sqrt(0.5)}};
  writeLp(dir / "a.lp", in);
  CHECK(readFile(dir / "a.lp", "t") ==
        "2\nIMG 0001.JPG 0.600000 0.000000 0.800000\nb.jpg -0.500000 0.500000 0.707107\n");
  const auto out = readLp(dir / "a.lp");
  REQUIRE(out.size() == 2);
  for (int i = 0; i < 2; ++i) {
    CHECK(out[i].filename == in[i].filename);
    CHECK(out[i].x == Approx(in[i].x).margin(1e-6));
    CHECK(out[i].z == Approx(in[i].z).margin(1e-6));
  }
  writeLp(dir / "b.lp", out);  // a second generation is byte-identical
  CHECK(readFile(dir / "b.lp", "t") == readFile(dir / "a.lp", "t"));
  CHECK_THROWS_AS(writeLp(dir / "c.lp", {{"bad\tname", 0, 0, 1}}), Error);
  CHECK_THROWS_AS(writeLp(dir / "c.lp", {}), Error);
  CHECK_FALSE(fs::exists(dir / "c.lp"));
  fs::remove_all(dir);
}

TEST_CASE("lp: every prefix and thousands of mutations parse or throw Error") {
  const std::string valid = "3\na b.jpg 0.1 0.2 0.9\nc.jpg -0.3 0.1 0.8\nd.jpg 0 -0.5 0.5\n";
  auto parse = [](const std::uint8_t* d, std::size_t n) {
    parseLp(std::string(reinterpret_cast<const char*>(d), n), "f.lp");
  };
  for (std::size_t n = 0; n <= valid.size(); ++n) test::parsesOrThrowsError(parse, valid.substr(0, n));
  test::fuzz(parse, valid, 20, 3000, 7);
}
