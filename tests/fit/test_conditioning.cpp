// A fit conditioned on its light set (src/fit/conditioning.h, docs/hrti-math.md "Conditioning
// on the light set"): plain least squares, bit for bit, for lights spread over the hemisphere;
// HSH order 3 damped toward order 2 for a narrow cone of lights, where plain least squares
// loses several dB to order 2 once its coefficients are quantised.
#include <catch2/catch.hpp>

#include <Eigen/Dense>
#include <cmath>
#include <random>

#include "fit/conditioning.h"
#include "fit/fit.h"
#include "fit/pseudo_inverse.h"
#include "reference_basis.h"
#include "synthetic.h"

using namespace surrogate;
using namespace surrogate::fit;
using test::Light;

namespace {

using Matrix = Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor>;

// The design from the reference closed forms (N x T, row-major).
std::vector<double> designOf(const std::vector<Light>& lights, Basis basis) {
  const int terms = basisTerms(basis);
  std::vector<double> a;
  for (const Light& l : lights) {
    for (int k = 0; k < terms; ++k) {
      if (isPtm(basis)) {
        const auto uv = reference::ptmArguments(l[0], l[1], l[2]);
        a.push_back(reference::ptmTerm(k, uv[0], uv[1]));
      } else {
        a.push_back(reference::hshTerm(k, l[0], l[1], l[2]));
      }
    }
  }
  return a;
}

// The noise gain written as a matrix expression: G^2 = (1/N) sum_k |A e_k|^2 |P^T e_k|_1^2.
double gainOf(const Matrix& a, const Matrix& p) {
  double sum = 0;
  for (Eigen::Index k = 0; k < a.cols(); ++k)
    sum += a.col(k).squaredNorm() * std::pow(p.row(k).lpNorm<1>(), 2);
  return std::sqrt(sum / static_cast<double>(a.rows()));
}

// 12 lights within 22 degrees of the view axis (elevations 68 to 85 degrees, all azimuths).
std::vector<Light> narrowCone() { return test::spiralLights(12, 68.0, 85.0); }

// A grey relief under the lights: Lambertian, albedo 0.35..0.9, normals tilted up to 35
// degrees, plus uniform noise of +-2 levels (what a camera adds), 8-bit samples.
MemoryImageStack relief(const std::vector<Light>& lights, int w, int h, std::vector<std::vector<double>>* samples) {
  std::mt19937 rng(11);
  std::uniform_real_distribution<double> u(0, 1);
  std::vector<std::array<double, 4>> surface;  // normal, albedo
  for (int p = 0; p < w * h; ++p) {
    const double tilt = 35 * M_PI / 180 * std::sqrt(u(rng)), dir = 2 * M_PI * u(rng);
    surface.push_back({std::sin(tilt) * std::cos(dir), std::sin(tilt) * std::sin(dir), std::cos(tilt), 0.35 + 0.55 * u(rng)});
  }
  std::vector<Image> images;
  samples->assign(w * h, {});
  for (const Light& l : lights) {
    Image im(w, h, 1);
    for (int p = 0; p < w * h; ++p) {
      const auto& s = surface[p];
      const double shade = std::max(0.0, s[0] * l[0] + s[1] * l[1] + s[2] * l[2]);
      const double v = std::round(std::clamp(255 * s[3] * shade + 4 * u(rng) - 2, 0.0, 255.0));
      im.pixels[p] = static_cast<std::uint16_t>(v * 257);
      (*samples)[p].push_back(v);
    }
    images.push_back(std::move(im));
  }
  return MemoryImageStack(std::move(images));
}

// The PSNR of plain least squares after quantisation, computed here from formats.md's HSH
// rule (SCALE = hi - lo, BIAS = lo, byte = round((a - BIAS) / SCALE * 255)) rather than by
// fitHsh: per pixel a = P s, each plane quantised over its range, re-rendered at the lights.
double plainQuantisedPsnr(const std::vector<std::vector<double>>& samples, const std::vector<Light>& lights,
                          Basis basis) {
  const int n = static_cast<int>(lights.size()), terms = basisTerms(basis);
  const std::vector<double> design = designOf(lights, basis);
  const Matrix a = Eigen::Map<const Matrix>(design.data(), n, terms);
  const Matrix p = a.completeOrthogonalDecomposition().pseudoInverse();
  Matrix coef(static_cast<Eigen::Index>(samples.size()), terms);
  for (std::size_t j = 0; j < samples.size(); ++j)
    coef.row(j) = p * (Eigen::Map<const Eigen::VectorXd>(samples[j].data(), n) / 255.0);
  for (int k = 0; k < terms; ++k) {
    const float bias = static_cast<float>(coef.col(k).minCoeff());
    const float scale = static_cast<float>(coef.col(k).maxCoeff() - coef.col(k).minCoeff());
    for (Eigen::Index j = 0; j < coef.rows(); ++j) {
      const double byte = std::clamp(std::round((coef(j, k) - bias) / scale * 255), 0.0, 255.0);
      coef(j, k) = byte / 255 * scale + bias;
    }
  }
  double err = 0;
  for (std::size_t j = 0; j < samples.size(); ++j)
    for (int i = 0; i < n; ++i) {
      const double v = std::clamp(255 * a.row(i).dot(coef.row(j)), 0.0, 255.0);
      err += (v - samples[j][i]) * (v - samples[j][i]);
    }
  return 20 * std::log10(255 / std::sqrt(err / (static_cast<double>(samples.size()) * n)));
}

}  // namespace

TEST_CASE("conditioning: the noise gain of an inverse is its closed form") {
  // The mean of N samples: one term, P = 1/N, g = 1, G = 1 (rounding the mean's samples).
  CHECK(noiseGain(std::vector<double>(5, 1.0), 5, 1, std::vector<double>(5, 0.2)) == Approx(1.0));
  // Two orthogonal columns of +-1 at four lights: P = A^T / 4, g_k = 1, |A e_k|^2 = 4, G = sqrt 2.
  const std::vector<double> a = {1, 1, 1, -1, 1, 1, 1, -1};
  const std::vector<double> p = {0.25, 0.25, 0.25, 0.25, 0.25, -0.25, 0.25, -0.25};
  CHECK(noiseGain(a, 4, 2, p) == Approx(std::sqrt(2.0)));
  // Scaling a term (a column of A by c, its row of P by 1/c) leaves G as it is.
  const std::vector<double> scaled = {1, 8, 1, -8, 1, 8, 1, -8};
  const std::vector<double> pScaled = {0.25, 0.25, 0.25, 0.25, 0.25 / 8, -0.25 / 8, 0.25 / 8, -0.25 / 8};
  CHECK(noiseGain(scaled, 4, 2, pScaled) == Approx(std::sqrt(2.0)));
}

TEST_CASE("conditioning: the damped inverse is (A^T A + mu N_D)^-1 A^T and tends to the lower order") {
  const auto lights = narrowCone();
  const std::vector<double> design = designOf(lights, Basis::Hsh3);
  const Matrix a = Eigen::Map<const Matrix>(design.data(), 12, 9);
  for (double mu : {1e-4, 0.1, 1.0, 10.0}) {
    // Normal equations, with the damped columns' squared norms on the diagonal.
    Eigen::MatrixXd normal = a.transpose() * a;
    for (int k = 4; k < 9; ++k) normal(k, k) += mu * a.col(k).squaredNorm();
    const Matrix expected = normal.ldlt().solve(Eigen::MatrixXd(a.transpose()));
    const PseudoInverse p = dampedPseudoInverse(design, 12, 9, {4, 5, 6, 7, 8}, mu);
    const Matrix got = Eigen::Map<const Matrix>(p.matrix.data(), 9, 12);
    CHECK((got - expected).norm() <= 1e-6 * expected.norm());
  }
  // mu -> infinity: the first four rows become HSH order 2's inverse, the other five vanish.
  const std::vector<double> lower = designOf(lights, Basis::Hsh2);
  const PseudoInverse p2 = pseudoInverse(lower, 12, 4);
  const PseudoInverse p3 = dampedPseudoInverse(design, 12, 9, {4, 5, 6, 7, 8}, 1e12);
  const Matrix order2 = Eigen::Map<const Matrix>(p2.matrix.data(), 4, 12);
  const Matrix damped = Eigen::Map<const Matrix>(p3.matrix.data(), 9, 12);
  CHECK((damped.topRows(4) - order2).norm() <= 1e-4 * order2.norm());
  CHECK(damped.bottomRows(5).norm() <= 1e-4 * order2.norm());
}

TEST_CASE("conditioning: lights spread over the hemisphere keep plain least squares, bit for bit") {
  for (int n : {9, 12, 20, 40}) {
    for (Basis b : {Basis::PtmLrgb, Basis::PtmRgb, Basis::Hsh2, Basis::Hsh3}) {
      if (n < basisTerms(b)) continue;
      const auto lights = test::spreadLights(n);
      std::vector<double> design;
      for (const Light& l : lights) {
        double w[9];
        if (isPtm(b)) {
          const auto t = ptmBasis(l[0], l[1]);
          std::copy(t.begin(), t.end(), w);
        } else {
          hshBasis(l[0], l[1], l[2], basisTerms(b), w);
        }
        design.insert(design.end(), w, w + basisTerms(b));
      }
      const Conditioning c = conditionedInverse(design, n, b);
      INFO(basisName(b) << " at " << n << " lights: noise gain " << c.plainNoiseGain);
      CHECK(c.plainNoiseGain < kMaxNoiseGain);
      CHECK(c.weight == 0.0);
      CHECK(c.damped.empty());
      CHECK(c.noiseGain == c.plainNoiseGain);
      CHECK(c.inverse.matrix == pseudoInverse(design, n, basisTerms(b)).matrix);  // the same bits
    }
  }
  // And the fit says so: weight 0, nothing damped, a finite condition number.
  const auto lights = test::spreadLights(20);
  const auto stack = test::hshImages(test::randomHsh(16, 12, 9, 3), lights);
  FitOptions o;
  o.basis = Basis::Hsh3;
  FitStatistics stats;
  fitHsh(stack, lights, o, &stats);
  CHECK(stats.regularisation == 0.0);
  CHECK(stats.dampedTerms.empty());
  CHECK(stats.conditionNumber > 1);
  CHECK(stats.conditionNumber < 20);
  CHECK(conditioningWarning(o.basis, 20, stats).empty());
  CHECK(stats.lightSpreadDegrees == Approx(90 - (20 + 60 * 0.5 / 20)).epsilon(1e-9));
}

TEST_CASE("conditioning: a narrow cone of lights damps HSH order 3 toward order 2") {
  const auto lights = narrowCone();
  std::vector<std::vector<double>> samples;
  const MemoryImageStack stack = relief(lights, 48, 40, &samples);
  FitOptions o2, o3;
  o2.basis = Basis::Hsh2;
  o3.basis = Basis::Hsh3;
  FitStatistics s2, s3;
  fitHsh(stack, lights, o2, &s2);
  fitHsh(stack, lights, o3, &s3);

  // This file's own quantisation reproduces the fit's PSNR where nothing is damped.
  CHECK(plainQuantisedPsnr(samples, lights, Basis::Hsh2) == Approx(s2.psnr).margin(0.02));
  // Plain least squares of order 3 loses several dB to order 2 once quantised ...
  const double plain3 = plainQuantisedPsnr(samples, lights, Basis::Hsh3);
  INFO("hsh2 " << s2.psnr << " dB, plain hsh3 " << plain3 << " dB, conditioned hsh3 " << s3.psnr << " dB");
  CHECK(plain3 < s2.psnr - 5);
  // ... the conditioned fit does not.
  CHECK(s3.psnr >= s2.psnr - 0.5);
  CHECK(s3.dampedTerms == std::vector<int>{4, 5, 6, 7, 8});
  CHECK(s3.regularisation > 0);
  CHECK(s2.regularisation == 0.0);  // order 2 has no lower order to tend to
  CHECK(s3.lightSpreadDegrees == Approx(90 - (68 + 17 * 0.5 / 12)).epsilon(1e-9));

  // The weight is the smallest of the ladder 2^j whose noise gain meets the target.
  const std::vector<double> design = designOf(lights, Basis::Hsh3), lower = designOf(lights, Basis::Hsh2);
  const Matrix a = Eigen::Map<const Matrix>(design.data(), 12, 9);
  const Matrix a2 = Eigen::Map<const Matrix>(lower.data(), 12, 4);
  const double target = std::max(kMaxNoiseGain, kLowerOrderMargin * gainOf(a2, a2.completeOrthogonalDecomposition().pseudoInverse()));
  auto gainAt = [&](double mu) {
    Eigen::MatrixXd normal = a.transpose() * a;
    for (int k = 4; k < 9; ++k) normal(k, k) += mu * a.col(k).squaredNorm();
    return gainOf(a, normal.ldlt().solve(Eigen::MatrixXd(a.transpose())));
  };
  CHECK(s3.plainNoiseGain == Approx(gainOf(a, a.completeOrthogonalDecomposition().pseudoInverse())).epsilon(1e-6));
  CHECK(s3.plainNoiseGain > 10 * kMaxNoiseGain);
  const int j = static_cast<int>(std::lround(std::log2(s3.regularisation)));
  CHECK(s3.regularisation == std::ldexp(1.0, j));
  CHECK(gainAt(s3.regularisation) <= target * (1 + 1e-9));
  CHECK(gainAt(std::ldexp(1.0, j - 1)) > target);
  CHECK(s3.noiseGain == Approx(gainAt(s3.regularisation)).epsilon(1e-6));
  const std::string warning = conditioningWarning(o3.basis, 12, s3);
  CHECK(warning.find("the 12 lights lie within 21 degrees of the view axis") == 0);
  CHECK(warning.find("HSH order 3's five highest terms were damped") != std::string::npos);
  // In the words of every warning (core/advice.h): usable or not, and what to do.
  CHECK(warning.find(". Usable with care: ") != std::string::npos);
  CHECK(warning.find(". What to do: ") != std::string::npos);
}
