#include "fit/conditioning.h"

#include <algorithm>
#include <cmath>
#include <iomanip>
#include <sstream>
#include <limits>
#include <string>

#include "core/advice.h"
#include "core/text.h"

namespace surrogate::fit {

namespace {
// The weight ladder 2^j, from 2^-34 (6e-11) to 2^20 (1e6): powers of two, exact on every
// machine (no libm function in the choice).
constexpr int kLadderLow = -34, kLadderHigh = 20;
}  // namespace

double noiseGain(const std::vector<double>& design, int n, int terms, const std::vector<double>& p) {
  double sum = 0;
  for (int k = 0; k < terms; ++k) {
    double range = 0, column = 0;
    for (int i = 0; i < n; ++i) {
      range += std::fabs(p[static_cast<std::size_t>(k) * n + i]);
      const double a = design[static_cast<std::size_t>(i) * terms + k];
      column += a * a;
    }
    sum += column * range * range;
  }
  return std::sqrt(sum / n);
}

std::vector<int> higherTerms(Basis basis) {
  switch (basis) {
    case Basis::PtmLrgb:
    case Basis::PtmRgb: return {0, 1, 2};
    case Basis::Hsh3: return {4, 5, 6, 7, 8};
    case Basis::Hsh2: return {};
  }
  return {};
}

Conditioning conditionedInverse(const std::vector<double>& design, int n, Basis basis) {
  const int terms = basisTerms(basis);
  Conditioning c;
  c.inverse = pseudoInverse(design, n, terms);
  const std::vector<double>& sigma = c.inverse.singularValues;
  c.conditionNumber = sigma.back() > 0 ? sigma.front() / sigma.back() : std::numeric_limits<double>::infinity();
  c.plainNoiseGain = c.noiseGain = noiseGain(design, n, terms, c.inverse.matrix);
  const std::vector<int> damped = higherTerms(basis);
  if (c.plainNoiseGain <= kMaxNoiseGain || damped.empty()) return c;

  // The lower-order fit: the design without the damped columns, its gain over the rest.
  const int lowerTerms = terms - static_cast<int>(damped.size());
  std::vector<double> lower;
  for (int i = 0; i < n; ++i)
    for (int k = 0; k < terms; ++k)
      if (std::find(damped.begin(), damped.end(), k) == damped.end())
        lower.push_back(design[static_cast<std::size_t>(i) * terms + k]);
  const double lowerGain = noiseGain(lower, n, lowerTerms, pseudoInverse(lower, n, lowerTerms).matrix);
  const double target = std::max(kMaxNoiseGain, kLowerOrderMargin * lowerGain);
  const int rank = c.inverse.rank;
  for (int j = kLadderLow; j <= kLadderHigh; ++j) {
    const double mu = std::ldexp(1.0, j);
    PseudoInverse p = dampedPseudoInverse(design, n, terms, damped, mu);
    const double gain = noiseGain(design, n, terms, p.matrix);
    if (gain <= target || j == kLadderHigh) {
      c.inverse = std::move(p);
      c.inverse.rank = rank;  // of the design, as reported
      c.noiseGain = gain;
      c.weight = mu;
      c.damped = damped;
      break;
    }
  }
  return c;
}

void recordConditioning(const Conditioning& c, const std::vector<std::array<double, 3>>& lights,
                        FitStatistics* stats) {
  if (!stats) return;
  stats->conditionNumber = c.conditionNumber;
  stats->noiseGain = c.noiseGain;
  stats->plainNoiseGain = c.plainNoiseGain;
  stats->regularisation = c.weight;
  stats->dampedTerms = c.damped;
  double lowest = 1;
  for (const auto& l : lights) lowest = std::min(lowest, l[2]);
  stats->lightSpreadDegrees = std::acos(std::clamp(lowest, -1.0, 1.0)) * 180.0 / M_PI;
}

std::string conditioningWarning(Basis basis, int lights, const FitStatistics& stats) {
  if (!(stats.regularisation > 0)) return "";
  const std::string terms = basis == Basis::Hsh3 ? "HSH order 3's five highest terms were damped toward order 2"
                                                 : "PTM's three quadratic terms were damped toward a plane";
  std::ostringstream weight;
  weight << std::setprecision(3) << stats.regularisation;
  return adviceText(
      {"the " + std::to_string(lights) + " lights lie within " + fixedDecimals(stats.lightSpreadDegrees, 0) +
           " degrees of the view axis, too narrow a cone for all the terms of " + basisName(basis) +
           " to survive being stored in 8 bits, so the fit kept the simpler terms and damped the others",
       Usable::WithCare,
       "the model relights well near the photographed lights, but raking light (low angles) shows less than the "
       "surface has",
       "for raking light, photograph the object again with lights at lower elevations as well",
       terms + " (weight " + weight.str() + ", quantisation noise gain " + fixedDecimals(stats.plainNoiseGain, 1) +
           " -> " + fixedDecimals(stats.noiseGain, 1) + "); PSNR " + fixedDecimals(stats.psnr, 2) + " dB"});
}

}  // namespace surrogate::fit
