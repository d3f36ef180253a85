#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <vector>

#include "core/error.h"
#include "fit/basis.h"
#include "fit/fit.h"
#include "fit/pseudo_inverse.h"
#include "fit/quantise.h"

using namespace surrogate;
using namespace surrogate::fit;

TEST_CASE("basis: names print and parse, unknown names are a usage error") {
  for (Basis b : {Basis::PtmLrgb, Basis::PtmRgb, Basis::Hsh2, Basis::Hsh3})
    CHECK(parseBasis(basisName(b)) == b);
  CHECK(basisTerms(Basis::Hsh3) == 9);
  CHECK(basisTerms(Basis::Hsh2) == 4);
  try {
    parseBasis("ptm");
    FAIL("accepted");
  } catch (const Error& e) {
    CHECK(e.kind() == ErrorKind::Usage);
  }
}

TEST_CASE("basis: PTM terms are (lu^2, lv^2, lu lv, lu, lv, 1)") {
  const auto w = ptmBasis(0.3, -0.5);
  CHECK(w[0] == Approx(0.09));
  CHECK(w[1] == Approx(0.25));
  CHECK(w[2] == Approx(-0.15));
  CHECK(w[3] == 0.3);
  CHECK(w[4] == -0.5);
  CHECK(w[5] == 1);
}

TEST_CASE("basis: HSH terms follow docs/hrti-math.md and clamp theta at pi/2 - 0.01") {
  const double theta = 0.7, phi = 2.1;
  double h[16];
  hshBasis(std::sin(theta) * std::cos(phi), std::sin(theta) * std::sin(phi), std::cos(theta), 16, h);
  const double c = std::cos(theta), s = std::sqrt(c - c * c), t = 2 * c - 1, pi = M_PI;
  CHECK(h[0] == Approx(1 / std::sqrt(2 * pi)));
  CHECK(h[1] == Approx(std::sqrt(6 / pi) * std::cos(phi) * s));
  CHECK(h[2] == Approx(std::sqrt(3 / (2 * pi)) * t));
  CHECK(h[3] == Approx(std::sqrt(6 / pi) * std::sin(phi) * s));
  CHECK(h[4] == Approx(std::sqrt(30 / pi) * std::cos(2 * phi) * (c * c - c)));
  CHECK(h[6] == Approx(std::sqrt(5 / (2 * pi)) * (6 * c * c - 6 * c + 1)));
  CHECK(h[8] == Approx(std::sqrt(30 / pi) * std::sin(2 * phi) * (c * c - c)));
  CHECK(h[12] == Approx(std::sqrt(7 / (2 * pi)) * (20 * c * c * c - 30 * c * c + 12 * c - 1)));
  CHECK(h[15] == Approx(2 * std::sqrt(35 / pi) * std::sin(3 * phi) * std::pow(c - c * c, 1.5)));
  // Grazing and below-horizon lights are evaluated at theta = pi/2 - 0.01.
  double grazing[9], clamped[9];
  hshBasis(1, 0, 0, 9, grazing);
  hshBasis(std::sin(kHshMaxTheta), 0, std::cos(kHshMaxTheta), 9, clamped);
  for (int k = 0; k < 9; ++k) CHECK(grazing[k] == Approx(clamped[k]).margin(1e-12));
  hshBasis(2, 0, -1, 9, grazing);  // unnormalised, below the horizon
  for (int k = 0; k < 9; ++k) CHECK(grazing[k] == Approx(clamped[k]).margin(1e-12));
}

TEST_CASE("fit options: parameters round trip, unknown ones are rejected") {
  FitOptions o;
  o.basis = Basis::Hsh3;
  const Parameters p = o.toParameters();
  REQUIRE(p.size() == 1);
  CHECK(p[0].first == "basis");
  CHECK(p[0].second == "hsh3");
  CHECK(FitOptions::fromParameters(p).basis == Basis::Hsh3);
  CHECK_THROWS_AS(FitOptions::fromParameters({{"basis", "rbf"}}), Error);
  CHECK_THROWS_AS(FitOptions::fromParameters({{"colour", "x"}}), Error);
}

TEST_CASE("quantise: no value of the range clips, error at most half a step") {
  for (auto [lo, hi] : {std::pair{-3.2, 140.7}, std::pair{5.0, 9.0}, std::pair{-50.0, -1.0},
                        std::pair{0.0, 0.0}}) {
    const PtmQuantisation q = choosePtmQuantisation(lo, hi);
    CHECK(q.bias >= 0);
    CHECK(q.bias <= 255);
    for (int i = 0; i <= 1000; ++i) {
      const double a = lo + (hi - lo) * i / 1000.0;
      CHECK(std::fabs(q.decode(q.quantise(a)) - a) <= q.scale / 2 + 1e-9);
    }
    const HshQuantisation hq = chooseHshQuantisation(lo / 255, hi / 255);
    for (int i = 0; i <= 1000; ++i) {
      const double a = (lo + (hi - lo) * i / 1000.0) / 255;
      CHECK(std::fabs(hq.decode(hq.quantise(a)) - a) <= hq.scale / 510.0 + 1e-6);
    }
  }
}

TEST_CASE("quantise: bytes round halves away from zero as std::lround and clamp to 0..255") {
  const PtmQuantisation unit;  // scale 1, bias 0: the byte is the rounded value itself
  std::vector<double> values = {-1.0, -0.5, 0.0, 254.5, 254.49999999999997, 255.0, 300.0,
                                std::nan("")};
  for (int i = 0; i <= 255 * 8; ++i) {
    const double v = i / 8.0;  // every quarter, half and three quarters
    values.insert(values.end(), {v, std::nextafter(v, -1.0), std::nextafter(v, 1000.0)});
  }
  for (double v : values) {
    const long expected = std::isnan(v) ? 0 : std::clamp(std::lround(v), 0L, 255L);
    CHECK(unit.quantise(v) == expected);
  }
}

TEST_CASE("16-bit samples round halves away from zero as std::lround and clamp to 0..65535") {
  // The normal map's samples (src/fit/normals.cpp): every half and its neighbours, the ends.
  std::vector<double> values = {-3.0, -0.5, 0.0, 65534.5, 65534.49999999999, 65535.0, 70000.0, 1e15};
  for (int i = 0; i <= 65535 * 2; ++i) {
    const double v = i / 2.0;
    values.insert(values.end(), {v, std::nextafter(v, -1.0), std::nextafter(v, 1e6)});
  }
  for (double v : values) {
    INFO(v);
    CHECK(fit::detail::roundClamped(v, 65535.0) == std::clamp(std::lround(v), 0L, 65535L));
  }
  CHECK(fit::detail::roundClamped(std::nan(""), 65535.0) == 0);
}

TEST_CASE("pseudo-inverse: recovers an exact linear model, reports rank deficiency") {
  // Lights all at one elevation: lu^2 + lv^2 is constant, so the PTM matrix has rank 5.
  std::vector<double> a;
  for (int i = 0; i < 12; ++i) {
    const double az = i * M_PI / 6, r = 0.6;
    const auto w = ptmBasis(r * std::cos(az), r * std::sin(az));
    a.insert(a.end(), w.begin(), w.end());
  }
  CHECK(pseudoInverse(a, 12, 6).rank == 5);
  a.clear();
  for (int i = 0; i < 12; ++i) {
    const double az = i * 2.4, r = 0.2 + 0.06 * i;
    const auto w = ptmBasis(r * std::cos(az), r * std::sin(az));
    a.insert(a.end(), w.begin(), w.end());
  }
  const auto p = pseudoInverse(a, 12, 6);
  CHECK(p.rank == 6);
  const double truth[6] = {-3, -2, 1, 4, 5, 100};
  for (int k = 0; k < 6; ++k) {
    double v = 0;
    for (int i = 0; i < 12; ++i) {
      double s = 0;
      for (int j = 0; j < 6; ++j) s += a[i * 6 + j] * truth[j];
      v += p.matrix[k * 12 + i] * s;
    }
    CHECK(v == Approx(truth[k]).margin(1e-9));
  }
}
