// The learned fit (fit/learned.h) against references outside it: the leave-one-out figure
// against refitting without each photograph, the viewer's weights against their closed forms,
// and the relit images against the surface the photographs were computed from, at lights the
// fit never saw.
#include <catch2/catch.hpp>

#include <cmath>
#include <random>

#include "core/error.h"
#include "fit/learned.h"
#include "fit/learned_interpolant.h"
#include "fit/learned_nodes.h"
#include "../light_spiral.h"

using namespace surrogate;
using Catch::WithinAbs;
using Light = std::array<double, 3>;

namespace {

// A surface whose response to a light is known in closed form: Lambertian albedo a(x, y) per
// channel with a normal tilted across the image, plus a Blinn-Phong lobe of exponent 8.
double surface(int x, int y, int c, const Light& l, int w, int h) {
  const double nx = 0.4 * (x - w / 2.0) / w, ny = 0.4 * (y - h / 2.0) / h;
  const double nn = std::sqrt(nx * nx + ny * ny + 1);
  const double n[3] = {nx / nn, ny / nn, 1 / nn};
  const double ndotl = std::max(0.0, n[0] * l[0] + n[1] * l[1] + n[2] * l[2]);
  double hx = l[0], hy = l[1], hz = l[2] + 1;
  const double hn = std::sqrt(hx * hx + hy * hy + hz * hz);
  const double ndoth = std::max(0.0, (n[0] * hx + n[1] * hy + n[2] * hz) / hn);
  const double albedo = 0.35 + 0.1 * c + 0.2 * ((x / 4 + y / 4) % 2);
  return std::min(1.0, albedo * ndotl + 0.15 * std::pow(ndoth, 8));
}

Image photograph(const Light& l, int w, int h) {
  Image im(w, h, 3);
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x)
      for (int c = 0; c < 3; ++c) im.at(x, y, c) = static_cast<std::uint16_t>(std::lround(surface(x, y, c, l, w, h) * 65535));
  return im;
}

double psnr8(const Image& a, const Image& b) {
  double se = 0;
  for (std::size_t i = 0; i < a.pixels.size(); ++i) {
    const double d = (a.pixels[i] - b.pixels[i]) / 257.0;
    se += d * d;
  }
  return 10 * std::log10(255.0 * 255.0 / (se / a.pixels.size()));
}

}  // namespace

TEST_CASE("the leave-one-out error of the interpolant equals refitting without each photograph") {
  const std::vector<Light> lights = test::spiralLights(24, 15.0, 80.0);
  const int N = static_cast<int>(lights.size());
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> u(0, 1);
  Eigen::MatrixXd samples(N, 40);
  for (int t = 0; t < 40; ++t)
    for (int i = 0; i < N; ++i) samples(i, t) = 0.2 + 0.5 * lights[i][2] + 0.1 * u(rng);
  const fit::Interpolant f = fit::chooseInterpolant(lights, samples * samples.transpose(), 40, 0.3, 0.01);
  // Brute force: the same kriging system without photograph i, evaluated at light i.
  double se = 0;
  for (int i = 0; i < N; ++i) {
    std::vector<Light> rest;
    Eigen::MatrixXd restSamples(N - 1, 40);
    for (int j = 0, r = 0; j < N; ++j)
      if (j != i) {
        rest.push_back(lights[j]);
        restSamples.row(r++) = samples.row(j);
      }
    const fit::Interpolant g = fit::chooseInterpolant(rest, restSamples * restSamples.transpose(), 40, 0.3, 0.01);
    REQUIRE(g.trendTerms == f.trendTerms);
    const Eigen::MatrixXd at = g.weightsAt({lights[i]}) * restSamples;  // 1 x 40
    se += (at.row(0) - samples.row(i)).squaredNorm();
  }
  CHECK_THAT(f.leaveOneOutMse, WithinAbs(se / (N * 40.0), 1e-9 + 1e-6 * se / (N * 40.0)));
}

TEST_CASE("the viewer weights follow their closed forms") {
  // A light on a grid node takes all of that node: node (x, y) = (3, 5) of a 9 x 9 grid.
  const Light node = fit::bilinearNodeDirection(9, 3, 5);
  const auto w = fit::bilinearNodeWeights(9, node);
  double onNode = 0;
  for (const auto& nw : w)
    if (nw.node == 3 + 5 * 9) onNode += nw.weight;
  CHECK_THAT(onNode, WithinAbs(1.0, 1e-9));
  // The view axis is the grid's centre: (u, v) = (0, 0) -> node ((R - 1) / 2, (R - 1) / 2).
  CHECK(fit::bilinearNodeDirection(9, 4, 4)[2] == 1.0);
  // RBF: two nodes at the same distance share the light equally.
  const std::vector<Light> nodes = {{0.6, 0, 0.8}, {-0.6, 0, 0.8}};
  const auto r = fit::rbfNodeWeights(nodes, {0, 0, 1});
  CHECK_THAT(r[0].weight, WithinAbs(0.5, 1e-12));
  CHECK_THAT(r[1].weight, WithinAbs(0.5, 1e-12));
}

TEST_CASE("a learned model relights lights it never saw close to the surface") {
  const int w = 40, h = 30;
  const std::vector<Light> all = test::spiralLights(60, 15.0, 80.0);
  std::vector<Light> fitted, unseen;
  std::vector<Image> photos;
  for (std::size_t i = 0; i < all.size(); ++i) {
    if (i % 6 == 3) {
      unseen.push_back(all[i]);
    } else {
      fitted.push_back(all[i]);
      photos.push_back(photograph(all[i], w, h));
    }
  }
  const MemoryImageStack stack(photos);
  for (const fit::LearnedKind kind : {fit::LearnedKind::Bilinear, fit::LearnedKind::Rbf}) {
    fit::LearnedOptions o;
    o.kind = kind;
    o.planes = 18;
    o.resolution = 12;
    fit::LearnedStatistics stats;
    const fit::LearnedModel m = fit::fitLearned(stack, fitted, o, &stats);
    CHECK(stats.explainedVariance > 0.99);
    double worst = 100;
    for (const Light& l : unseen) worst = std::min(worst, psnr8(fit::renderLearned(m, l), photograph(l, w, h)));
    INFO(fit::learnedKindName(kind) << " worst unseen light " << worst << " dB");
    // The surface's lobe is sharper than the lights' spacing; the viewer's RBF blends more widely
    // than the bilinear grid (measured 27.6 and 43.9 dB).
    CHECK(worst > (kind == fit::LearnedKind::Rbf ? 25 : 40));
    // The same bytes at any thread count.
    o.threads = 1;
    const fit::LearnedModel one = fit::fitLearned(stack, fitted, o);
    o.threads = 2;
    const fit::LearnedModel two = fit::fitLearned(stack, fitted, o);
    CHECK(one.coefficients == two.coefficients);
    CHECK(one.basis == two.basis);
    CHECK(one.coefficients == m.coefficients);
  }
}

TEST_CASE("a learned fit refuses what it cannot fit, naming the option") {
  const std::vector<Light> lights = test::spiralLights(8, 20.0, 80.0);
  std::vector<Image> photos;
  for (const Light& l : lights) photos.push_back(photograph(l, 8, 6));
  const MemoryImageStack stack(photos);
  fit::LearnedOptions o;
  o.planes = 10;
  CHECK_THROWS_AS(fit::fitLearned(stack, lights, o), Error);
  o.planes = 27;  // 8 photographs hold 3 N - 3 = 21
  CHECK(fit::fitLearned(stack, lights, o).planes == 21);
  CHECK(fit::learnedPlanesFor(45, 12) == 33);
  o.planes = 9;
  std::vector<Light> below = lights;
  below[2] = {0.8, 0, -0.6};
  CHECK_THROWS_AS(fit::fitLearned(stack, below, o), Error);
  CHECK(fit::LearnedOptions::fromParameters(o.toParameters()).planes == 9);
}
