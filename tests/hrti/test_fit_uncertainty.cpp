// The standard errors the front end states for its estimates (hrti/circle_fit.h,
// DetectedSphere::centreSigmaPx, Highlight::covXX..): against the spread of repeated estimates
// and the closed forms for a circle through noisy points, and their ordering for highlights.
#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <random>

#include "hrti/circle_fit.h"
#include "hrti/highlight_detection.h"
#include "hrti/sphere_detection.h"

using namespace surrogate;
using namespace surrogate::hrti;

TEST_CASE("the circle fit's standard errors match the spread of repeated fits") {
  // n points evenly round a circle, each moved radially by independent noise of sd s: the
  // closed forms are sd(cx) = sd(cy) = s sqrt(2 / n), sd(r) = s / sqrt(n).
  constexpr int kPoints = 90, kTrials = 400;
  constexpr double kNoise = 0.3, kR = 100;
  std::mt19937 rng(11);
  std::normal_distribution<double> noise(0, kNoise);
  double sumCx = 0, sumCx2 = 0, sumR = 0, sumR2 = 0, statedCx = 0, statedR = 0;
  for (int t = 0; t < kTrials; ++t) {
    std::vector<Point2> p;
    for (int k = 0; k < kPoints; ++k) {
      const double a = 2 * M_PI * (k + 0.37 * t) / kPoints, d = kR + noise(rng);
      p.push_back({50 + d * std::cos(a), 60 + d * std::sin(a)});
    }
    const CircleFit f = fitCircle(p, 10);  // no outliers: every point kept
    REQUIRE(f.ok);
    REQUIRE(f.inliers == kPoints);
    sumCx += f.cx;
    sumCx2 += f.cx * f.cx;
    sumR += f.r;
    sumR2 += f.r * f.r;
    statedCx += f.sigmaCx / kTrials;
    statedR += f.sigmaR / kTrials;
  }
  const double sdCx = std::sqrt(sumCx2 / kTrials - std::pow(sumCx / kTrials, 2));
  const double sdR = std::sqrt(sumR2 / kTrials - std::pow(sumR / kTrials, 2));
  CHECK(statedCx == Approx(kNoise * std::sqrt(2.0 / kPoints)).epsilon(0.1));
  CHECK(statedR == Approx(kNoise / std::sqrt(double(kPoints))).epsilon(0.1));
  CHECK(sdCx == Approx(statedCx).epsilon(0.15));
  CHECK(sdR == Approx(statedR).epsilon(0.15));
}

namespace {

const DetectedSphere kSphere{60, 60, 45, 1};

// A dark sphere's body (0.03) with a spot of peak `peak` (clipped at full scale), sd `sx`, `sy`.
Image spot(double peak, double sx, double sy) {
  Image im(120, 120, 1);
  for (int y = 0; y < 120; ++y)
    for (int x = 0; x < 120; ++x) {
      const double dx = (x - 70.3) / sx, dy = (y - 50.6) / sy;
      const double v = 0.03 + peak * std::exp(-(dx * dx + dy * dy) / 2);
      im.at(x, y) = static_cast<std::uint16_t>(std::lround(std::clamp(v, 0.0, 1.0) * 65535));
    }
  return im;
}

}  // namespace

TEST_CASE("a highlight's stated covariance grows when it is clipped or elongated") {
  const Highlight round = detectHighlight(spot(0.9, 3, 3), 0, 0, kSphere, HighlightOptions());
  const Highlight clipped = detectHighlight(spot(6, 2, 2), 0, 0, kSphere, HighlightOptions());
  const Highlight streak = detectHighlight(spot(0.9, 6, 2), 0, 0, kSphere, HighlightOptions());
  REQUIRE(isUsable(round.flag));
  REQUIRE(isUsable(clipped.flag));
  REQUIRE(isUsable(streak.flag));
  // The unclipped round spot: its centre within a fraction of a pixel, and the stated
  // covariance positive, round, and under a pixel squared.
  CHECK(std::hypot(round.x - 70.3, round.y - 50.6) < 0.15);
  CHECK(round.covXX > 0);
  CHECK(round.covXX == Approx(round.covYY).epsilon(0.1));
  CHECK(std::abs(round.covXY) < 0.1 * round.covXX);
  CHECK(round.covXX < 1);
  // A clipped core (about as wide as the round one's) hides where its peak is.
  CHECK(clipped.covXX > 2 * round.covXX);
  // A streak along x is uncertain along x more than across it.
  CHECK(streak.covXX > 3 * streak.covYY);
}
