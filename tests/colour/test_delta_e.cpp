// CIEDE2000 against the 34 test pairs of Sharma, Wu and Dalal (2005), Table 1 ("The CIEDE2000
// color-difference formula: implementation notes, supplementary test data, and mathematical
// observations", Color Res. Appl. 30(1) 21-30; data also at
// http://www2.ece.rochester.edu/~gsharma/ciede2000/), to the table's 4 decimals.
#include <catch2/catch.hpp>

#include <cmath>

#include "colour/delta_e.h"

using namespace surrogate::colour;

namespace {
struct Pair {
  Lab first, second;
  double deltaE;
};
const Pair kSharma[34] = {
    {{50.0000, 2.6772, -79.7751}, {50.0000, 0.0000, -82.7485}, 2.0425},
    {{50.0000, 3.1571, -77.2803}, {50.0000, 0.0000, -82.7485}, 2.8615},
    {{50.0000, 2.8361, -74.0200}, {50.0000, 0.0000, -82.7485}, 3.4412},
    {{50.0000, -1.3802, -84.2814}, {50.0000, 0.0000, -82.7485}, 1.0000},
    {{50.0000, -1.1848, -84.8006}, {50.0000, 0.0000, -82.7485}, 1.0000},
    {{50.0000, -0.9009, -85.5211}, {50.0000, 0.0000, -82.7485}, 1.0000},
    {{50.0000, 0.0000, 0.0000}, {50.0000, -1.0000, 2.0000}, 2.3669},
    {{50.0000, -1.0000, 2.0000}, {50.0000, 0.0000, 0.0000}, 2.3669},
    {{50.0000, 2.4900, -0.0010}, {50.0000, -2.4900, 0.0009}, 7.1792},
    {{50.0000, 2.4900, -0.0010}, {50.0000, -2.4900, 0.0010}, 7.1792},
    {{50.0000, 2.4900, -0.0010}, {50.0000, -2.4900, 0.0011}, 7.2195},
    {{50.0000, 2.4900, -0.0010}, {50.0000, -2.4900, 0.0012}, 7.2195},
    {{50.0000, -0.0010, 2.4900}, {50.0000, 0.0009, -2.4900}, 4.8045},
    {{50.0000, -0.0010, 2.4900}, {50.0000, 0.0010, -2.4900}, 4.8045},
    {{50.0000, -0.0010, 2.4900}, {50.0000, 0.0011, -2.4900}, 4.7461},
    {{50.0000, 2.5000, 0.0000}, {50.0000, 0.0000, -2.5000}, 4.3065},
    {{50.0000, 2.5000, 0.0000}, {73.0000, 25.0000, -18.0000}, 27.1492},
    {{50.0000, 2.5000, 0.0000}, {61.0000, -5.0000, 29.0000}, 22.8977},
    {{50.0000, 2.5000, 0.0000}, {56.0000, -27.0000, -3.0000}, 31.9030},
    {{50.0000, 2.5000, 0.0000}, {58.0000, 24.0000, 15.0000}, 19.4535},
    {{50.0000, 2.5000, 0.0000}, {50.0000, 3.1736, 0.5854}, 1.0000},
    {{50.0000, 2.5000, 0.0000}, {50.0000, 3.2972, 0.0000}, 1.0000},
    {{50.0000, 2.5000, 0.0000}, {50.0000, 1.8634, 0.5757}, 1.0000},
    {{50.0000, 2.5000, 0.0000}, {50.0000, 3.2592, 0.3350}, 1.0000},
    {{60.2574, -34.0099, 36.2677}, {60.4626, -34.1751, 39.4387}, 1.2644},
    {{63.0109, -31.0961, -5.8663}, {62.8187, -29.7946, -4.0864}, 1.2630},
    {{61.2901, 3.7196, -5.3901}, {61.4292, 2.2480, -4.9620}, 1.8731},
    {{35.0831, -44.1164, 3.7933}, {35.0232, -40.0716, 1.5901}, 1.8645},
    {{22.7233, 20.0904, -46.6940}, {23.0331, 14.9730, -42.5619}, 2.0373},
    {{36.4612, 47.8580, 18.3852}, {36.2715, 50.5065, 21.2231}, 1.4146},
    {{90.8027, -2.0831, 1.4410}, {91.1528, -1.6435, 0.0447}, 1.4441},
    {{90.9257, -0.5406, -0.9208}, {88.6381, -0.8985, -0.7239}, 1.5381},
    {{6.7747, -0.2908, -2.4247}, {5.8714, -0.0985, -2.2286}, 0.6377},
    {{2.0776, 0.0795, -1.1350}, {0.9033, -0.0636, -0.5514}, 0.9082},
};
}  // namespace

TEST_CASE("CIEDE2000 gives the 34 pairs of Sharma Wu and Dalal") {
  for (int i = 0; i < 34; ++i) {
    INFO("pair " << i + 1);
    const Pair& p = kSharma[i];
    // The table gives 4 decimals: within 0.5e-4 of the exact value, plus rounding of ours.
    CHECK(deltaE2000(p.first, p.second) == Approx(p.deltaE).margin(1e-4));
    CHECK(deltaE2000(p.second, p.first) == Approx(p.deltaE).margin(1e-4));  // symmetric
  }
}

TEST_CASE("CIEDE2000 and CIE76 of identical colours and of a pure lightness step") {
  const Lab grey{50, 0, 0};
  CHECK(deltaE2000(grey, grey) == 0);
  CHECK(deltaE76(grey, grey) == 0);
  // At L* = 50 the lightness weight S_L is 1: a pure L* step of 3 is dE2000 3.
  CHECK(deltaE2000({48.5, 0, 0}, {51.5, 0, 0}) == Approx(3.0).margin(1e-12));
  // CIE76: Euclidean distance, a 3-4-12 box has diagonal 13.
  CHECK(deltaE76({50, 10, -20}, {53, 14, -8}) == Approx(13.0).margin(1e-12));
}

TEST_CASE("CIEDE2000 with unit lightness weight counts lightness steps whole") {
  // Sharma pairs 1-16 and 21-24 lie at L* = 50, where S_L is 1 anyway: both agree there.
  for (int i = 0; i < 24; ++i)
    if (kSharma[i].first.L == 50 && kSharma[i].second.L == 50)
      CHECK(deltaE2000UnitSL(kSharma[i].first, kSharma[i].second) ==
            Approx(deltaE2000(kSharma[i].first, kSharma[i].second)).margin(1e-12));
  // A pure L* step of 3 around L* = 91.5 (white patch): 3 with S_L = 1; the standard formula
  // divides by S_L = 1 + 0.015 * 41.5^2 / sqrt(20 + 41.5^2) = 1.6189
  const Lab a{90, 0, 0}, b{93, 0, 0};
  CHECK(deltaE2000UnitSL(a, b) == Approx(3.0).margin(1e-12));
  const double sL = 1 + 0.015 * 41.5 * 41.5 / std::sqrt(20 + 41.5 * 41.5);
  CHECK(deltaE2000(a, b) == Approx(3.0 / sL).margin(1e-12));
  // Chroma and hue differences are untouched by S_L.
  CHECK(deltaE2000UnitSL({90, 10, 0}, {90, 12, 1}) ==
        Approx(deltaE2000({90, 10, 0}, {90, 12, 1})).margin(1e-12));
}
