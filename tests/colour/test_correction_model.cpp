// The chart fit against what is known without it: a cast made by a known matrix is undone
// exactly, a hand-solvable case gives its closed form, the white-point constraint holds to
// rounding, and the root-polynomial model ignores exposure.
#include <catch2/catch.hpp>

#include "colour/chart_reference.h"
#include "colour/correction_model.h"
#include "core/error.h"

using namespace surrogate;
using namespace surrogate::colour;

namespace {

const std::vector<int> kNeutrals{18, 19, 20, 21, 22};

Rgb times(const double (&m)[3][3], const Rgb& v) {
  Rgb r{0, 0, 0};
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) r[i] += m[i][j] * v[j];
  return r;
}

std::vector<Rgb> chartSrgb() {
  const auto a = referenceLinearSrgb(chartReference(kDefaultChartReference));
  return {a.begin(), a.end()};
}

// A camera: the chart's linear sRGB through a cast (a warm light and crosstalk between the
// channels), the reference values clamped at 0 first (cyan's red) as a sensor would.
std::vector<Rgb> castCamera(const std::vector<Rgb>& srgb, const double (&cast)[3][3]) {
  std::vector<Rgb> m;
  for (Rgb v : srgb) {
    for (double& x : v) x = std::max(x, 0.0);
    m.push_back(times(cast, v));
  }
  return m;
}

// Small, fixed disturbances of the references (a fit that cannot be exact).
std::vector<Rgb> disturbed(std::vector<Rgb> v) {
  for (size_t k = 0; k < v.size(); ++k)
    for (int i = 0; i < 3; ++i) v[k][i] *= 1.0 + 0.03 * std::sin(1.7 * k + 2.3 * i);
  return v;
}

const double kCast[3][3] = {{0.90, 0.15, 0.02}, {0.10, 0.80, 0.08}, {0.03, 0.12, 0.55}};

}  // namespace

TEST_CASE("a cast made by a known matrix is undone exactly") {
  std::vector<Rgb> reference = chartSrgb();
  for (Rgb& v : reference)
    for (double& x : v) x = std::max(x, 0.0);
  const std::vector<Rgb> measured = castCamera(reference, kCast);
  for (ColourModelKind kind : {ColourModelKind::Matrix, ColourModelKind::RootPolynomial}) {
    const ColourModel model = fitColourModel(measured, reference, kind, kNeutrals);
    CHECK(model.terms() == (kind == ColourModelKind::Matrix ? 3 : 6));
    for (size_t k = 0; k < measured.size(); ++k) {
      const Rgb out = model.apply(measured[k]);
      for (int i = 0; i < 3; ++i) CHECK(out[i] == Approx(reference[k][i]).margin(1e-10));
    }
    if (kind == ColourModelKind::Matrix) {
      // M = cast^-1; its first row from the cofactors of the cast, det by hand:
      // 0.9(0.44-0.0096) - 0.15(0.055-0.0024) + 0.02(0.012-0.024) = 0.38736-0.00789-0.00024.
      const double det = 0.90 * (0.80 * 0.55 - 0.08 * 0.12) - 0.15 * (0.10 * 0.55 - 0.08 * 0.03) +
                         0.02 * (0.10 * 0.12 - 0.80 * 0.03);
      CHECK(det == Approx(0.37923).margin(1e-12));
      CHECK(model.coefficients[0] == Approx((0.80 * 0.55 - 0.08 * 0.12) / det).margin(1e-10));
      CHECK(model.coefficients[1] == Approx(-(0.15 * 0.55 - 0.02 * 0.12) / det).margin(1e-10));
      CHECK(model.coefficients[2] == Approx((0.15 * 0.08 - 0.02 * 0.80) / det).margin(1e-10));
    }
  }
}

TEST_CASE("the constrained fit gives the closed form of a hand solvable case") {
  // Patches e1, e2, e3 and the neutral (1,1,1). Row i minimises sum_j (x_j - y_j)^2 subject to
  // x_1 + x_2 + x_3 = w (the neutral's own residual is then 0), so x_j = y_j + (w - sum y)/3.
  const std::vector<Rgb> measured{{1, 0, 0}, {0, 1, 0}, {0, 0, 1}, {1, 1, 1}};
  const std::vector<Rgb> reference{{0.7, 0.1, 0.0}, {0.2, 0.6, 0.1}, {0.0, 0.2, 0.9}, {1, 1, 1}};
  const ColourModel m = fitColourModel(measured, reference, ColourModelKind::Matrix, {3});
  for (int i = 0; i < 3; ++i) {
    const double sum = reference[0][i] + reference[1][i] + reference[2][i];
    for (int j = 0; j < 3; ++j)
      CHECK(m.coefficients[static_cast<size_t>(3 * i + j)] ==
            Approx(reference[static_cast<size_t>(j)][i] + (1.0 - sum) / 3.0).margin(1e-12));
  }
}

TEST_CASE("the summed neutrals map exactly onto their summed references") {
  const std::vector<Rgb> reference = disturbed(chartSrgb());
  const std::vector<Rgb> measured = castCamera(chartSrgb(), kCast);
  for (ColourModelKind kind : {ColourModelKind::Matrix, ColourModelKind::RootPolynomial}) {
    const ColourModel model = fitColourModel(measured, reference, kind, kNeutrals);
    Rgb mw{0, 0, 0}, rw{0, 0, 0};
    for (int k : kNeutrals)
      for (int i = 0; i < 3; ++i) {
        mw[i] += measured[static_cast<size_t>(k)][i];
        rw[i] += reference[static_cast<size_t>(k)][i];
      }
    const Rgb out = model.apply(mw);
    for (int i = 0; i < 3; ++i) CHECK(out[i] == Approx(rw[i]).margin(1e-12));
  }
}

TEST_CASE("the root polynomial fit does not depend on exposure") {
  const std::vector<Rgb> reference = disturbed(chartSrgb());
  const std::vector<Rgb> measured = castCamera(chartSrgb(), kCast);
  std::vector<Rgb> brighter = measured;
  for (Rgb& v : brighter)
    for (double& x : v) x *= 2.5;
  const ColourModel a = fitColourModel(measured, reference, ColourModelKind::RootPolynomial,
                                       kNeutrals);
  const ColourModel b = fitColourModel(brighter, reference, ColourModelKind::RootPolynomial,
                                       kNeutrals);
  for (size_t k = 0; k < measured.size(); ++k) {
    const Rgb x = a.apply(measured[k]), y = b.apply(brighter[k]), z = a.apply(brighter[k]);
    for (int i = 0; i < 3; ++i) {
      CHECK(y[i] == Approx(x[i]).margin(1e-12));        // same corrected colours
      CHECK(z[i] == Approx(2.5 * x[i]).margin(1e-12));  // and the model scales with light
    }
  }
}

TEST_CASE("too few or too alike patches are an input error") {
  const std::vector<Rgb> reference = chartSrgb();
  const std::vector<Rgb> measured = castCamera(reference, kCast);
  std::vector<bool> use(24, false);
  for (int k : {0, 1, 2, 3, 4, 18}) use[static_cast<size_t>(k)] = true;  // 6 patches
  try {
    fitColourModel(measured, reference, ColourModelKind::RootPolynomial, kNeutrals, use);
    FAIL("no exception");
  } catch (const Error& e) {
    CHECK(e.kind() == ErrorKind::Input);
  }
  use[5] = true;  // 7 = terms + 1
  CHECK_NOTHROW(
      fitColourModel(measured, reference, ColourModelKind::RootPolynomial, kNeutrals, use));
  // Only the greys: every patch on one line through black.
  std::vector<bool> greys(24, false);
  for (int k = 18; k < 24; ++k) greys[static_cast<size_t>(k)] = true;
  std::vector<Rgb> greyMeasured = measured;
  for (int k = 18; k < 24; ++k) {
    const double v = 0.9 - 0.15 * (k - 18);
    greyMeasured[static_cast<size_t>(k)] = {v, v, v};
  }
  try {
    fitColourModel(greyMeasured, reference, ColourModelKind::Matrix, kNeutrals, greys);
    FAIL("no exception");
  } catch (const Error& e) {
    CHECK(e.kind() == ErrorKind::Input);
  }
  CHECK_THROWS_AS(fitColourModel(measured, reference, ColourModelKind::Matrix, {}), Error);
  CHECK(parseModelName("root-polynomial", "--colour-model") == ColourModelKind::RootPolynomial);
  CHECK_THROWS_AS(parseModelName("polynomial", "--colour-model"), Error);
}

TEST_CASE("leave one out refits without the patch and keeps the neutrals") {
  std::vector<Rgb> exact = chartSrgb();
  for (Rgb& v : exact)
    for (double& x : v) x = std::max(x, 0.0);
  const std::vector<Rgb> measured = castCamera(exact, kCast);
  // Exact data: any 23 patches still determine the cast, so every patch comes out exact.
  const std::vector<Rgb> loo = leaveOneOut(measured, exact, ColourModelKind::Matrix, kNeutrals);
  for (size_t k = 0; k < loo.size(); ++k)
    for (int i = 0; i < 3; ++i) CHECK(loo[k][i] == Approx(exact[k][i]).margin(1e-10));
  // Disturbed data: a neutral gets the full fit's value, another patch the fit without it.
  const std::vector<Rgb> reference = disturbed(exact);
  const std::vector<Rgb> out = leaveOneOut(measured, reference, ColourModelKind::Matrix, kNeutrals);
  const ColourModel full = fitColourModel(measured, reference, ColourModelKind::Matrix, kNeutrals);
  std::vector<bool> without(24, true);
  without[7] = false;
  const ColourModel partial =
      fitColourModel(measured, reference, ColourModelKind::Matrix, kNeutrals, without);
  for (int i = 0; i < 3; ++i) {
    CHECK(out[19][i] == Approx(full.apply(measured[19])[i]).margin(1e-14));
    CHECK(out[7][i] == Approx(partial.apply(measured[7])[i]).margin(1e-14));
  }
  CHECK(out[7][0] != Approx(full.apply(measured[7])[0]).margin(1e-9));
}
