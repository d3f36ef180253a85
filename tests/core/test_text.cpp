#include <catch2/catch.hpp>

#include <cmath>
#include <limits>
#include <string>

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
