// fit::ptmBasis, fit::hshBasis and fit::evaluatePtm checked term by term against the closed
// forms of tests/fit/reference_basis.h (written from Malzbender et al. 2001 / HP's PTM format
// for PTM, from Gautron et al. 2004 and RTIViewer's getHSH for HSH; see that header and
// docs/hrti-math.md), at many light directions. Every term is compared on its own, so a
// sign flip, a swap or a wrong constant in a single term fails here even though the fit and
// the synthetic photographs of other tests would agree with each other.
#include <catch2/catch.hpp>

#include <cmath>
#include <vector>

#include "fit/basis.h"
#include "fit/ptm_math.h"
#include "reference_basis.h"

using namespace surrogate;
namespace ref = surrogate::reference;

namespace {

struct Direction {
  double lx, ly, lz;
};

// Polar angles over the whole upper hemisphere (pole, near the pole, mid elevations, near
// and past relight's clamp at pi/2 - 0.01, below the horizon), azimuths in all four quadrants
// (negative ly gives negative atan2), and three vector lengths (the basis normalises).
std::vector<Direction> manyDirections() {
  std::vector<Direction> out;
  const double thetas[] = {0.0, 0.02, 0.17, 0.35, 0.52, 0.7, 0.85, 1.0, 1.13,
                           1.27, 1.4, 1.5, 1.555, 1.565, 1.58, 1.9, 2.6};
  const double phis[] = {-3.1, -2.5, -1.9, -1.2, -0.8, -0.3, 0.0, 0.25, 0.6,
                         0.95, 1.4, 1.8, 2.2, 2.75, ref::kPi};
  const double lengths[] = {1.0, 0.37, 4.2};
  int i = 0;
  for (double theta : thetas)
    for (double phi : phis) {
      const double r = lengths[i++ % 3];
      out.push_back({r * std::sin(theta) * std::cos(phi), r * std::sin(theta) * std::sin(phi),
                     r * std::cos(theta)});
    }
  // The axes and the image's edges, as the .lp convention names them (y to the TOP).
  for (Direction d : {Direction{0, 0, 1}, Direction{1, 0, 0.2}, Direction{-1, 0, 0.2},
                      Direction{0, 1, 0.2}, Direction{0, -1, 0.2}, Direction{0.6, 0.6, 0.5},
                      Direction{-0.3, 0.8, 0.52}, Direction{0.2, -0.4, 0.89}})
    out.push_back(d);
  return out;
}

std::string describe(const Direction& d) {
  return "light (" + std::to_string(d.lx) + ", " + std::to_string(d.ly) + ", " +
         std::to_string(d.lz) + ")";
}

}  // namespace

TEST_CASE("reference: RTIViewer's HSH table equals Gautron's construction for all 16 terms") {
  // The two ways of writing the reference agree, so neither carries a typo the other lacks.
  for (const Direction& d : manyDirections()) {
    const ref::Angles a = ref::hshAngles(d.lx, d.ly, d.lz);
    for (int k = 0; k < 16; ++k) {
      INFO(describe(d) << ", term H" << k);
      CHECK(ref::hshTable(k, a.theta, a.phi) ==
            Approx(ref::hshGautron(k, a.theta, a.phi)).epsilon(1e-12).margin(1e-12));
    }
  }
}

TEST_CASE("basis: every HSH term of orders 2, 3 and 4 equals its closed form at many lights") {
  const auto directions = manyDirections();
  for (int terms : {4, 9, 16}) {
    for (const Direction& d : directions) {
      double h[17];
      for (double& v : h) v = 1234.5;  // sentinel: nothing past `terms` is written
      fit::hshBasis(d.lx, d.ly, d.lz, terms, h);
      const ref::Angles a = ref::hshAngles(d.lx, d.ly, d.lz);
      for (int k = 0; k < terms; ++k) {
        INFO(terms << " terms, " << describe(d) << ", term H" << k);
        CHECK(h[k] == Approx(ref::hshTable(k, a.theta, a.phi)).epsilon(1e-12).margin(1e-12));
        CHECK(h[k] == Approx(ref::hshGautron(k, a.theta, a.phi)).epsilon(1e-12).margin(1e-12));
      }
      for (int k = terms; k < 17; ++k) CHECK(h[k] == 1234.5);
    }
  }
}

TEST_CASE("basis: HSH terms 0 to 15 one by one at lights from the right, the top and above") {
  // Hand-checkable values: at phi = 0 every sin term is 0 and every cos term is its radial
  // factor; at phi = pi/2 (a light from the TOP of the image) the reverse for odd m.
  const double theta = 0.9, c = std::cos(theta), s = std::sqrt(c - c * c), t = 2 * c - 1;
  const double pi = ref::kPi;
  double right[16], top[16], above[16];
  fit::hshBasis(std::sin(theta), 0, std::cos(theta), 16, right);
  fit::hshBasis(0, std::sin(theta), std::cos(theta), 16, top);
  fit::hshBasis(0, 0, 1, 16, above);
  const double radial[16] = {1 / std::sqrt(2 * pi),
                             std::sqrt(6 / pi) * s,
                             std::sqrt(3 / (2 * pi)) * t,
                             std::sqrt(6 / pi) * s,
                             std::sqrt(30 / pi) * (c * c - c),
                             std::sqrt(30 / pi) * t * s,
                             std::sqrt(5 / (2 * pi)) * (6 * c * c - 6 * c + 1),
                             std::sqrt(30 / pi) * t * s,
                             std::sqrt(30 / pi) * (c * c - c),
                             2 * std::sqrt(35 / pi) * std::pow(c - c * c, 1.5),
                             std::sqrt(210 / pi) * t * (c * c - c),
                             2 * std::sqrt(21 / pi) * s * (5 * c * c - 5 * c + 1),
                             std::sqrt(7 / (2 * pi)) * (20 * c * c * c - 30 * c * c + 12 * c - 1),
                             2 * std::sqrt(21 / pi) * s * (5 * c * c - 5 * c + 1),
                             std::sqrt(210 / pi) * t * (c * c - c),
                             2 * std::sqrt(35 / pi) * std::pow(c - c * c, 1.5)};
  // Angular factor of term k at phi = 0 and at phi = pi/2 (cos(m phi) or sin(m phi)).
  const double atRight[16] = {1, 1, 1, 0, 1, 1, 1, 0, 0, 1, 1, 1, 1, 0, 0, 0};
  const double atTop[16] = {1, 0, 1, 1, -1, 0, 1, 1, 0, 0, -1, 0, 1, 1, 0, -1};
  for (int k = 0; k < 16; ++k) {
    INFO("term H" << k);
    CHECK(right[k] == Approx(atRight[k] * radial[k]).margin(1e-12));
    CHECK(top[k] == Approx(atTop[k] * radial[k]).margin(1e-12));
  }
  // Straight above: c = 1, s = 0, t = 1. Only the m = 0 terms remain.
  const double pole[16] = {1 / std::sqrt(2 * pi), 0, std::sqrt(3 / (2 * pi)), 0, 0, 0,
                           std::sqrt(5 / (2 * pi)), 0, 0, 0, 0, 0, std::sqrt(7 / (2 * pi)),
                           0, 0, 0};
  for (int k = 0; k < 16; ++k) {
    INFO("term H" << k << " at the pole");
    CHECK(above[k] == Approx(pole[k]).margin(1e-12));
  }
}

TEST_CASE("basis: the HSH terms are orthonormal over the upper hemisphere (Gautron et al.)") {
  // int H_i H_j sin(theta) dtheta dphi over theta in [0, pi/2] = delta_ij: checks every
  // normalisation constant against the definition, not against a table. Midpoint rule in
  // c = cos(theta) (the surviving integrands are polynomials in c) and in phi (exact for the
  // trigonometric factors). fit::hshBasis is integrated where it does not clamp
  // (c >= cos(pi/2 - 0.01)); the thin band below, where it evaluates at the clamp, is
  // integrated with the unclamped construction of reference_basis.h.
  const double c0 = std::cos(ref::kMaxTheta) + 1e-12;
  const int nc = 2000, nphi = 64;
  std::vector<double> gram(16 * 16, 0.0);
  auto accumulate = [&](double lo, double hi, bool useFit) {
    for (int i = 0; i < nc; ++i) {
      const double c = lo + (hi - lo) * (i + 0.5) / nc, st = std::sqrt(1 - c * c);
      for (int j = 0; j < nphi; ++j) {
        const double phi = 2 * ref::kPi * (j + 0.5) / nphi;
        double h[16];
        if (useFit) {
          fit::hshBasis(st * std::cos(phi), st * std::sin(phi), c, 16, h);
        } else {
          for (int k = 0; k < 16; ++k) h[k] = ref::hshGautron(k, std::acos(c), phi);
        }
        const double w = (hi - lo) / nc * (2 * ref::kPi / nphi);
        for (int a = 0; a < 16; ++a)
          for (int b = 0; b < 16; ++b) gram[a * 16 + b] += w * h[a] * h[b];
      }
    }
  };
  accumulate(c0, 1.0, true);
  accumulate(0.0, c0, false);
  for (int a = 0; a < 16; ++a)
    for (int b = 0; b < 16; ++b) {
      INFO("terms H" << a << " and H" << b);
      CHECK(gram[a * 16 + b] == Approx(a == b ? 1.0 : 0.0).margin(1e-5));
    }
}

TEST_CASE("basis: every PTM term equals its closed form at many lights, in the file's order") {
  // PTM file order (HP PTM format 1.2): a0..a5 multiply lu^2, lv^2, lu lv, lu, lv, 1.
  std::vector<std::pair<double, double>> points;
  for (double lu : {-1.4, -1.0, -0.71, -0.33, -0.05, 0.0, 0.12, 0.4, 0.66, 0.93, 1.25})
    for (double lv : {-1.3, -0.9, -0.55, -0.2, 0.0, 0.07, 0.3, 0.61, 0.88, 1.1})
      points.emplace_back(lu, lv);
  for (auto [lu, lv] : points) {
    const auto w = fit::ptmBasis(lu, lv);
    for (int k = 0; k < 6; ++k) {
      INFO("(lu, lv) = (" << lu << ", " << lv << "), term a" << k);
      CHECK(w[k] == Approx(ref::ptmTerm(k, lu, lv)).epsilon(1e-14).margin(1e-15));
      // The renderer's polynomial uses the same order: coefficient vector e_k gives term k.
      fit::PtmCoefficients unit{};
      unit[k] = 1;
      CHECK(fit::evaluatePtm(unit, lu, lv) == Approx(ref::ptmTerm(k, lu, lv)).epsilon(1e-14).margin(1e-15));
    }
  }
}

TEST_CASE("basis: PTM terms at a light from the right and from the top of the image") {
  // (lu, lv) = (lx, ly): a light from the right has lv = 0, one from the top has lu = 0.
  const auto ar = ref::ptmArguments(0.6, 0.0, 0.8), at = ref::ptmArguments(0.0, 1.2, 1.6);
  const auto right = fit::ptmBasis(ar[0], ar[1]), top = fit::ptmBasis(at[0], at[1]);
  const double wantRight[6] = {0.36, 0, 0, 0.6, 0, 1}, wantTop[6] = {0, 0.36, 0, 0, 0.6, 1};
  for (int k = 0; k < 6; ++k) {
    INFO("term a" << k);
    CHECK(right[k] == Approx(wantRight[k]).margin(1e-15));
    CHECK(top[k] == Approx(wantTop[k]).margin(1e-15));
  }
}
