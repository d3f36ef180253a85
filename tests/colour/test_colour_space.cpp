// Colour spaces pinned to published numbers: the IEC 61966-2-1 matrix, Lindbloom's tables
// (brucelindbloom.com: the sRGB matrix and Bradford D65 -> D50, computed with the same whites
// as ours) and CIELAB of the sRGB primaries as Lindbloom's calculator gives them.
#include <catch2/catch.hpp>

#include "colour/colour_space.h"

using namespace surrogate::colour;

namespace {
// Column c of a linear map: its image of the unit vector c.
template <typename F>
void checkMatrix(F f, const double (&expected)[3][3], double tolerance) {
  for (int c = 0; c < 3; ++c) {
    std::array<double, 3> unit{0, 0, 0};
    unit[c] = 1;
    const std::array<double, 3> column = f(unit);
    for (int r = 0; r < 3; ++r) CHECK(column[r] == Approx(expected[r][c]).margin(tolerance));
  }
}
}  // namespace

TEST_CASE("the sRGB transfer follows IEC 61966-2-1") {
  CHECK(srgbDecode(0.0) == 0.0);
  CHECK(srgbDecode(1.0) == Approx(1.0).margin(1e-15));
  CHECK(srgbDecode(0.04045) == Approx(0.04045 / 12.92).margin(1e-15));
  CHECK(srgbDecode(0.5) == Approx(0.214041140).margin(1e-9));  // ((0.5+0.055)/1.055)^2.4
  CHECK(srgbEncode(0.0031308) == Approx(0.0031308 * 12.92).margin(1e-12));
  CHECK(srgbEncode(0.18) == Approx(0.461356129).margin(1e-9));  // 1.055*0.18^(1/2.4)-0.055
  CHECK(srgbEncode(-0.2) == 0.0);
  CHECK(srgbDecode(1.3) == Approx(1.0));
}

TEST_CASE("linear sRGB to XYZ matches the IEC table and Lindbloom") {
  // IEC 61966-2-1:1999, 4 digits. Its blue Z (0.9505) is rounded to put white at Z 1.0890; the
  // matrix scaled to the tabulated D65 (Z 1.08883) has 0.95030, hence the 2.1e-4.
  const double iec[3][3] = {{0.4124, 0.3576, 0.1805},
                            {0.2126, 0.7152, 0.0722},
                            {0.0193, 0.1192, 0.9505}};
  checkMatrix(xyzD65FromLinearSrgb, iec, 2.1e-4);
  // Lindbloom, RGB/XYZ matrices, sRGB (D65 = 0.95047, 1, 1.08883), 7 digits.
  const double lindbloom[3][3] = {{0.4124564, 0.3575761, 0.1804375},
                                  {0.2126729, 0.7151522, 0.0721750},
                                  {0.0193339, 0.1191920, 0.9503041}};
  checkMatrix(xyzD65FromLinearSrgb, lindbloom, 1e-7);
  const double inverse[3][3] = {{3.2404542, -1.5371385, -0.4985314},
                                {-0.9692660, 1.8760108, 0.0415560},
                                {0.0556434, -0.2040259, 1.0572252}};
  checkMatrix(linearSrgbFromXyzD65, inverse, 1e-6);
  const Xyz white = xyzD65FromLinearSrgb({1, 1, 1});
  for (int i = 0; i < 3; ++i) CHECK(white[i] == Approx(kWhiteD65[i]).margin(1e-12));
}

TEST_CASE("Bradford adaptation matches Lindbloom") {
  // Lindbloom, Chromatic Adaptation, Bradford, D65 -> D50 and D50 -> D65.
  const double toD50[3][3] = {{1.0478112, 0.0228866, -0.0501270},
                              {0.0295424, 0.9904844, -0.0170491},
                              {-0.0092345, 0.0150436, 0.7521316}};
  checkMatrix(adaptD65ToD50, toD50, 1e-7);
  const double toD65[3][3] = {{0.9555766, -0.0230393, 0.0631636},
                              {-0.0282895, 1.0099416, 0.0210077},
                              {0.0122982, -0.0204830, 1.3299098}};
  checkMatrix(adaptD50ToD65, toD65, 1e-7);
  const Xyz w = adaptD65ToD50(kWhiteD65);
  for (int i = 0; i < 3; ++i) CHECK(w[i] == Approx(kWhiteD50[i]).margin(1e-12));
}

TEST_CASE("CIELAB of known colours") {
  // L* of mid grey in closed form: 116 * 0.18^(1/3) - 16.
  Lab grey = labD50FromLinearSrgb({0.18, 0.18, 0.18});
  CHECK(grey.L == Approx(49.496107).margin(1e-6));
  CHECK(grey.a == Approx(0).margin(1e-9));
  CHECK(grey.b == Approx(0).margin(1e-9));
  // Below the knee (Y < 216/24389) L* = 24389/27 Y.
  CHECK(labFromXyz({0.0048211, 0.005, 0.0041261}, kWhiteD50).L ==
        Approx(24389.0 / 27.0 * 0.005).margin(1e-9));
  // The sRGB primaries under D65 (Lindbloom's calculator, sRGB, ref. white D65).
  const Lab red = labFromXyz(xyzD65FromLinearSrgb({1, 0, 0}), kWhiteD65);
  CHECK(red.L == Approx(53.2408).margin(1e-4));
  CHECK(red.a == Approx(80.0925).margin(1e-4));
  CHECK(red.b == Approx(67.2032).margin(1e-4));
  const Lab green = labFromXyz(xyzD65FromLinearSrgb({0, 1, 0}), kWhiteD65);
  CHECK(green.L == Approx(87.7347).margin(1e-4));
  CHECK(green.a == Approx(-86.1827).margin(1e-4));
  CHECK(green.b == Approx(83.1793).margin(1e-4));
  const Lab blue = labFromXyz(xyzD65FromLinearSrgb({0, 0, 1}), kWhiteD65);
  CHECK(blue.L == Approx(32.2970).margin(1e-4));
  CHECK(blue.a == Approx(79.1875).margin(1e-4));
  CHECK(blue.b == Approx(-107.8602).margin(1e-4));
  // The same red under D50 via Bradford (Lindbloom's calculator, ref. white D50, Bradford).
  const Lab red50 = labD50FromLinearSrgb({1, 0, 0});
  CHECK(red50.L == Approx(54.2917).margin(1e-4));
  CHECK(red50.a == Approx(80.8125).margin(1e-4));
  CHECK(red50.b == Approx(69.8851).margin(1e-4));
}

TEST_CASE("Lab and linear sRGB convert back and forth") {
  for (const Rgb& rgb : {Rgb{0.2, 0.5, 0.9}, Rgb{0.003, 0.004, 0.002}, Rgb{-0.04, 0.23, 0.38}}) {
    const Rgb back = linearSrgbFromLabD50(labD50FromLinearSrgb(rgb));
    for (int i = 0; i < 3; ++i) CHECK(back[i] == Approx(rgb[i]).margin(1e-12));
  }
}
