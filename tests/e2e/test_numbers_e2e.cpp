// Every number Surrogate records is written with the fewest digits that read back as the same
// double (formatNumber, src/core/text.h): a real run's carrier, its lights.lp and `info --json`
// hold no "0.80000000000000004".
#include <catch2/catch.hpp>

#include <cctype>
#include <cstdio>
#include <cstdlib>
#include <regex>
#include <string>
#include <vector>

#include "core/text.h"
#include "e2e_support.h"

namespace fs = std::filesystem;
using namespace surrogate;

namespace {

// A decimal number as the writers spell one: no leading zeros, no '+', optional exponent (hashes,
// stems such as "0001", dates and versions like "1.2.3" do not match).
const std::regex kNumber(R"(-?(0|[1-9][0-9]*)(\.[0-9]+)?([eE][+-]?[0-9]+)?)");

// Significant digits of a number's text: leading zeros and the zeros that only place the point
// ("1000000", "0.0025") are not digits the value needs.
int significantDigits(const std::string& text) {
  std::string digits;
  for (char c : text) {
    if (c == 'e' || c == 'E') break;
    if (c >= '0' && c <= '9') digits += c;
  }
  const auto first = digits.find_first_not_of('0');
  if (first == std::string::npos) return 1;
  digits = digits.substr(first);
  return static_cast<int>(digits.find_last_not_of('0') + 1);
}

// The fewest significant digits printf needs for `v` to read back exactly: a count made without
// formatNumber, so the check does not only compare the formatter with itself.
int fewestDigits(double v) {
  char buffer[64];
  for (int precision = 1; precision < 17; ++precision) {
    std::snprintf(buffer, sizeof buffer, "%.*e", precision - 1, v);
    if (std::strtod(buffer, nullptr) == v) return precision;
  }
  return 17;
}

// The pieces of `text` between spaces, commas, semicolons, quotes and tags that are numbers.
std::vector<std::string> numbersIn(const std::string& text) {
  std::vector<std::string> out;
  const std::regex piece(R"([^\s,;"<>=]+)");
  for (auto it = std::sregex_iterator(text.begin(), text.end(), piece); it != std::sregex_iterator(); ++it) {
    const std::string p = it->str();
    if (std::regex_match(p, kNumber)) out.push_back(p);
  }
  return out;
}

// The numbers of an XML document's attributes whose whole value is a number or a list of numbers
// ("0.8", "2.1 1 1.5", "X,Y,W,H"): prose such as log messages, which show rounded figures for
// people, and version attributes ("1.0" is a name, not a number) are left out.
std::string numericAttributes(const std::string& xml) {
  std::string out;
  // Attribute values are read by hand: libstdc++'s recursive std::regex is not for long texts.
  for (std::size_t at = xml.find("=\""); at != std::string::npos; at = xml.find("=\"", at + 2)) {
    std::size_t nameStart = at;
    while (nameStart > 0 && !std::isspace(static_cast<unsigned char>(xml[nameStart - 1]))) --nameStart;
    const std::string name = xml.substr(nameStart, at - nameStart);
    const std::size_t end = xml.find('"', at + 2);
    if (end == std::string::npos) break;
    const std::string value = xml.substr(at + 2, end - at - 2);
    if (name.find("ersion") != std::string::npos) continue;
    std::vector<std::string> pieces;
    std::string piece;
    for (char c : value + " ") {
      if (c == ' ' || c == ',' || c == ';' || c == '\n' || c == '\t') {
        if (!piece.empty()) pieces.push_back(piece);
        piece.clear();
      } else {
        piece += c;
      }
    }
    bool allNumbers = !pieces.empty();
    for (const std::string& p : pieces)
      if (!std::regex_match(p, kNumber)) allNumbers = false;
    if (allNumbers) out += value + "\n";
  }
  return out;
}

// The numbers of `text` that have more digits than they need to read back.
std::vector<std::string> longNumbers(const std::string& text, std::size_t& checked) {
  std::vector<std::string> bad;
  for (const std::string& n : numbersIn(text)) {
    const double v = std::strtod(n.c_str(), nullptr);
    // Integers above 2^53 (none are recorded) and counts written as integers are exact as they are.
    if (n.find_first_of(".eE") == std::string::npos) continue;
    ++checked;
    if (n != formatNumber(v) || significantDigits(n) > fewestDigits(v)) bad.push_back(n);
  }
  return bad;
}

}  // namespace

TEST_CASE("a real run records every number with no more digits than it needs to read back") {
  const fs::path capture = e2e::smallCapture(e2e::freshDir("numbers"));
  const e2e::CommandResult r = e2e::surrogate(
      "run " + e2e::quote(capture) +
      " --title Numbers --highlight-threshold 0.8 --crop auto --crop-margin 0.3 --resize 0.7 --quiet");
  INFO(r.output);
  REQUIRE(r.exitCode == 0);

  const std::string xml = e2e::bytesOf(capture / "assembly-files/carrier.xml");
  std::size_t checked = 0;
  CHECK(longNumbers(numericAttributes(xml), checked).empty());
  CHECK(checked > 50);  // light directions, highlights, spheres, fit statistics, timings
  // The parameters given on the command line are recorded as typed.
  CHECK(xml.find("\"0.8\"") != std::string::npos);
  CHECK(xml.find("\"0.3\"") != std::string::npos);
  CHECK(xml.find("0.80000000000000004") == std::string::npos);

  std::size_t lpChecked = 0;
  const std::string lp = e2e::bytesOf(capture / "assembly-files/lights.lp");
  CHECK(longNumbers(lp, lpChecked).empty());
  CHECK(lpChecked >= 8 * 3);

  const e2e::CommandResult info = e2e::surrogate("info " + e2e::quote(capture / "assembly-files/lights.lp") + " --json");
  REQUIRE(info.exitCode == 0);
  std::size_t jsonChecked = 0;
  CHECK(longNumbers(info.output, jsonChecked).empty());
}

TEST_CASE("the number check itself finds a number written with 17 digits") {
  std::size_t checked = 0;
  CHECK(longNumbers(numericAttributes("<param name=\"threshold\" value=\"0.80000000000000004\"/>"), checked) ==
        std::vector<std::string>{"0.80000000000000004"});
  CHECK(longNumbers(numericAttributes("<x a=\"0.8\" b=\"2.5 1 0.125\" c=\"1e-07\" version=\"1.0\" "
                                      "m=\"RMSE 1.230\"/>"),
                    checked)
            .empty());
  CHECK(numericAttributes("<x b=\"2.5 1 0.125\" m=\"RMSE 1.230\"/>") == "2.5 1 0.125\n");
  CHECK(longNumbers("a.lp 0.500000 0.250000 0.829156", checked) ==
        std::vector<std::string>{"0.500000", "0.250000"});
}
