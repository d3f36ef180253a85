#include <catch2/catch.hpp>

#include <cmath>

#include "core/error.h"
#include "fit/fit.h"
#include "fit/pseudo_inverse.h"
#include "../rows_only_stack.h"
#include "synthetic.h"

using namespace surrogate;
using namespace surrogate::fit;
using test::Light;

namespace {
// sum_i |P_ki| for the basis at these lights: how much per-sample noise can move coefficient k.
std::vector<double> noiseGain(const std::vector<Light>& lights, int terms, bool ptm) {
  std::vector<double> a;
  for (const Light& l : lights) {
    double w[16];
    if (ptm) {
      const auto b = ptmBasis(l[0], l[1]);
      std::copy(b.begin(), b.end(), w);
    } else {
      hshBasis(l[0], l[1], l[2], terms, w);
    }
    a.insert(a.end(), w, w + terms);
  }
  const auto p = pseudoInverse(a, static_cast<int>(lights.size()), terms);
  std::vector<double> g(terms, 0.0);
  for (int k = 0; k < terms; ++k)
    for (std::size_t i = 0; i < lights.size(); ++i) g[k] += std::fabs(p.matrix[k * lights.size() + i]);
  return g;
}
}  // namespace

TEST_CASE("fit: RGB PTM built from known polynomials is recovered within quantisation") {
  const auto lights = test::spreadLights(30);
  const auto truth = test::randomPtm(24, 16, 1);
  const auto stack = test::ptmImages(truth, lights);
  FitOptions o;
  o.basis = Basis::PtmRgb;
  FitStatistics stats;
  const formats::PtmFile ptm = fitPtm(stack, lights, o, &stats);
  REQUIRE(ptm.format == formats::PtmFile::Format::Rgb);
  const auto gain = noiseGain(lights, 6, true);
  double worst = 0;
  for (int y = 0; y < 16; ++y)
    for (int x = 0; x < 24; ++x)
      for (int c = 0; c < 3; ++c)
        for (int k = 0; k < 6; ++k) {
          const double err = std::fabs(ptm.coefficient(x, y, k, c) - truth.coef[(y * 24 + x) * 3 + c][k]);
          const double bound = ptm.scale[k] / 2 + gain[k] * 0.5 / 257 + 1e-9;
          worst = std::max(worst, err / bound);
        }
  CHECK(worst <= 1.0);
  CHECK(stats.rank == 6);
  CHECK(stats.perImageRmse.size() == 30);
  CHECK(stats.rmse < 0.5);
  CHECK(stats.psnr > 45);
  for (double r : stats.perImageRmse) CHECK(r < 1.0);
}

TEST_CASE("fit: LRGB recovers the colour and the luminance polynomial (relight's definition)") {
  const auto lights = test::spreadLights(30);
  const int w = 12, h = 10;
  std::mt19937 rng(5);
  std::uniform_real_distribution<double> u(0, 1);
  std::vector<std::array<double, 6>> lum;
  std::vector<std::array<double, 3>> colour;
  for (int p = 0; p < w * h; ++p) {
    lum.push_back({-20 * u(rng), -20 * u(rng), -5 + 10 * u(rng), -20 + 40 * u(rng),
                   -20 + 40 * u(rng), 230 + 30 * u(rng)});
    colour.push_back({100 + 100 * u(rng), 100 + 100 * u(rng), 100 + 100 * u(rng)});
  }
  std::vector<Image> images;
  for (const Light& l : lights) {
    Image im(w, h, 3);
    for (int p = 0; p < w * h; ++p)
      for (int c = 0; c < 3; ++c)
        im.pixels[p * 3 + c] = test::sample255(colour[p][c] * test::evalPtm(lum[p], l) / 255.0);
    images.push_back(std::move(im));
  }
  const MemoryImageStack stack(std::move(images));
  std::vector<double> weight;
  double total = 0;
  for (const Light& l : lights) {
    const double e = std::asin(l[2]) / (M_PI / 2) - 0.5;
    weight.push_back(std::max(0.0, 0.25 - e * e));
    total += weight.back();
  }
  FitStatistics stats;
  const formats::PtmFile ptm = fitPtm(stack, lights, FitOptions{}, &stats);
  REQUIRE(ptm.format == formats::PtmFile::Format::Lrgb);
  const auto gain = noiseGain(lights, 6, true);
  for (int p = 0; p < w * h; ++p) {
    double lw = 0;
    for (std::size_t i = 0; i < lights.size(); ++i) lw += weight[i] * test::evalPtm(lum[p], lights[i]);
    lw /= total;
    double stored = 0, sum = 0;
    for (int c = 0; c < 3; ++c) {
      const double expected = colour[p][c] * lw / 255.0;
      CHECK(std::fabs(ptm.rgb[p * 3 + c] - expected) <= 0.51);
      stored += ptm.rgb[p * 3 + c];
      sum += colour[p][c];
    }
    const double noise = 255.0 * (3 * 0.5 / 257) / stored;
    for (int k = 0; k < 6; ++k) {
      const double expected = lum[p][k] * sum / stored;
      CHECK(std::fabs(ptm.coefficient(p % w, p / w, k) - expected) <=
            ptm.scale[k] / 2 + gain[k] * noise + 1e-9);
    }
  }
  CHECK(stats.psnr > 45);
}

TEST_CASE("fit: HSH (4 and 9 terms) built from known coefficients is recovered") {
  const auto lights = test::spreadLights(40);
  for (Basis b : {Basis::Hsh2, Basis::Hsh3}) {
    const int terms = basisTerms(b);
    const auto truth = test::randomHsh(16, 12, terms, 3);
    const auto stack = test::hshImages(truth, lights);
    FitOptions o;
    o.basis = b;
    FitStatistics stats;
    const formats::HshFile hsh = fitHsh(stack, lights, o, &stats);
    REQUIRE(hsh.terms == terms);
    const auto gain = noiseGain(lights, terms, false);
    double worst = 0;
    for (int y = 0; y < 12; ++y)
      for (int x = 0; x < 16; ++x)
        for (int c = 0; c < 3; ++c)
          for (int k = 0; k < terms; ++k) {
            const double err = std::fabs(hsh.coefficient(x, y, c, k) - truth.coef[(y * 16 + x) * 3 + c][k]);
            const double bound = hsh.scale[k] / 510.0 + gain[k] * 0.5 / 65535 + 1e-6;
            worst = std::max(worst, err / bound);
          }
    CHECK(worst <= 1.0);
    CHECK(stats.psnr > 45);
    CHECK(stats.rank == terms);
  }
}

TEST_CASE("fit: results are bit-identical for 1 or 2 threads and any memory budget") {
  // The default budget keeps pass 1's coefficients for pass 2 (fit.h); the small ones fit twice.
  const auto lights = test::spreadLights(20);
  const auto truth = test::randomPtm(40, 33, 9);
  const auto stack = test::ptmImages(truth, lights);
  for (Basis b : {Basis::PtmLrgb, Basis::PtmRgb, Basis::Hsh3}) {
    FitOptions big;
    big.basis = b;
    big.threads = 1;
    FitOptions small = big;
    small.memoryBudgetBytes = 1;  // one-row bands
    small.threads = 2;
    FitOptions mid = big;
    mid.memoryBudgetBytes = 20 * 40 * 3 * 2 * 7 + 200000;  // a few rows per band
    mid.threads = 2;
    // More budgets, for other band heights.
    FitOptions tight = mid;
    tight.memoryBudgetBytes = 40000;
    FitOptions roomy = mid;
    roomy.memoryBudgetBytes = 100000;
    FitStatistics s1, s2, s3, s4;
    if (isPtm(b)) {
      const auto a = fitPtm(stack, lights, big, &s1);
      CHECK(a == fitPtm(stack, lights, small, &s2));
      CHECK(a == fitPtm(stack, lights, mid, &s3));
      CHECK(a == fitPtm(stack, lights, tight, &s4));
      CHECK(a == fitPtm(stack, lights, roomy));
    } else {
      const auto a = fitHsh(stack, lights, big, &s1);
      CHECK(a == fitHsh(stack, lights, small, &s2));
      CHECK(a == fitHsh(stack, lights, mid, &s3));
      CHECK(a == fitHsh(stack, lights, tight, &s4));
      CHECK(a == fitHsh(stack, lights, roomy));
    }
    CHECK(s1.passes == 1);
    CHECK(s2.passes == 2);
    CHECK(s1.rmse == s2.rmse);
    CHECK(s1.perImageRmse == s2.perImageRmse);
    CHECK(s1.perImageRmse == s3.perImageRmse);
    CHECK(s1.perImageRmse == s4.perImageRmse);
  }
}

TEST_CASE("fit: images read in place give the model they give copied in bands") {
  const auto lights = test::spreadLights(20);
  const auto stack = test::ptmImages(test::randomPtm(40, 33, 9), lights);
  // The same images behind another ImageStack: the fit copies them into row bands instead of
  // reading the MemoryImageStack in place.
  const test::RowsOnlyStack copied(stack);
  for (Basis b : {Basis::PtmLrgb, Basis::PtmRgb, Basis::Hsh3}) {
    FitOptions whole;
    whole.basis = b;
    FitOptions bands = whole;
    bands.memoryBudgetBytes = 20 * 40 * 3 * 2 * 7 + 200000;  // a few rows per band
    for (const FitOptions& o : {whole, bands}) {
      FitStatistics inPlace, inBands;
      if (isPtm(b)) CHECK(fitPtm(stack, lights, o, &inPlace) == fitPtm(copied, lights, o, &inBands));
      else CHECK(fitHsh(stack, lights, o, &inPlace) == fitHsh(copied, lights, o, &inBands));
      CHECK(inPlace.perImageRmse == inBands.perImageRmse);
      CHECK(inPlace.passes == inBands.passes);
    }
  }
}

TEST_CASE("fit: progress is reported up to 1, grey stacks are fitted as R = G = B") {
  const auto lights = test::spreadLights(12);
  std::vector<Image> grey;
  for (const Light& l : lights) {
    Image im(5, 4, 1);
    for (auto& v : im.pixels) v = test::sample255(100 + 50 * l[0]);
    grey.push_back(im);
  }
  const MemoryImageStack stack(std::move(grey));
  FitOptions o;
  o.basis = Basis::PtmRgb;
  o.memoryBudgetBytes = 1;
  double last = 0;
  int calls = 0;
  o.progress = [&](double f) {
    CHECK(f >= last);
    last = f;
    ++calls;
  };
  FitStatistics stats;
  const auto ptm = fitPtm(stack, lights, o, &stats);
  CHECK(last == 1.0);
  CHECK(calls == 8);  // 4 bands, two passes
  CHECK(ptm.coefficient(2, 2, 3, 0) == Approx(50).margin(ptm.scale[3]));
  CHECK(ptm.coefficient(2, 2, 3, 2) == ptm.coefficient(2, 2, 3, 0));
}

TEST_CASE("fit: bad inputs are reported as errors") {
  const auto lights = test::spreadLights(8);
  const auto stack = test::ptmImages(test::randomPtm(4, 4, 2), lights);
  FitOptions o;
  auto fewer = lights;
  fewer.pop_back();
  CHECK_THROWS_AS(fitPtm(stack, fewer, o), Error);
  auto zero = lights;
  zero[3] = {0, 0, 0};
  CHECK_THROWS_AS(fitPtm(stack, zero, o), Error);
  o.basis = Basis::Hsh3;  // 9 terms > 8 photographs
  CHECK_THROWS_AS(fitHsh(stack, lights, o), Error);
  CHECK_THROWS_AS(fitPtm(stack, lights, o), Error);
  const MemoryImageStack empty({});
  CHECK_THROWS_AS(fitPtm(empty, {}, FitOptions{}), Error);
}
