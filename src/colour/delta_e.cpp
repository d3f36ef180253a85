// CIEDE2000 and CIE76 colour differences. See delta_e.h.
//
// The equations are numbered as in Sharma, Wu and Dalal (2005), section 2 ("computation of
// CIEDE2000 color difference"), with kL = kC = kH = 1. Hue angles are in degrees as there.
#include "colour/delta_e.h"

#include <cmath>

namespace surrogate::colour {
namespace {

constexpr double kPi = 3.14159265358979323846;
constexpr double kTwentyFiveToTheSeventh = 6103515625.0;  // 25^7

double radians(double degrees) { return degrees * kPi / 180.0; }

// Hue angle in [0, 360); 0 for a neutral (a' = b' = 0), as the paper specifies (eq. 4).
double hueDegrees(double b, double aPrime) {
  if (b == 0 && aPrime == 0) return 0;
  double h = std::atan2(b, aPrime) * 180.0 / kPi;
  return h < 0 ? h + 360.0 : h;
}

// unitLightnessWeight: S_L = 1 instead of its function of L* (Metamorfoze 2.0's variant).
double ciede2000(const Lab& reference, const Lab& sample, bool unitLightnessWeight) {
  // (1)-(4): a' stretched by G near the neutral axis, then C' and h'.
  const double c1 = std::hypot(reference.a, reference.b);
  const double c2 = std::hypot(sample.a, sample.b);
  const double cMean7 = std::pow((c1 + c2) / 2.0, 7.0);
  const double g = 0.5 * (1.0 - std::sqrt(cMean7 / (cMean7 + kTwentyFiveToTheSeventh)));
  const double a1 = (1.0 + g) * reference.a;
  const double a2 = (1.0 + g) * sample.a;
  const double cp1 = std::hypot(a1, reference.b);
  const double cp2 = std::hypot(a2, sample.b);
  const double h1 = hueDegrees(reference.b, a1);
  const double h2 = hueDegrees(sample.b, a2);

  // (8)-(10): differences; the hue difference is 0 when either colour is neutral.
  const double dL = sample.L - reference.L;
  const double dC = cp2 - cp1;
  const bool neutral = cp1 * cp2 == 0;
  double dh = 0;
  if (!neutral) {
    dh = h2 - h1;
    if (dh > 180.0) dh -= 360.0;
    else if (dh < -180.0) dh += 360.0;
  }
  const double dH = 2.0 * std::sqrt(cp1 * cp2) * std::sin(radians(dh / 2.0));

  // (12)-(22): means (the hue mean across 0/360 as in eq. 14) and the weighting functions.
  const double lMean = (reference.L + sample.L) / 2.0;
  const double cpMean = (cp1 + cp2) / 2.0;
  double hMean = h1 + h2;
  if (!neutral) {
    if (std::abs(h1 - h2) > 180.0) hMean += hMean < 360.0 ? 360.0 : -360.0;
    hMean /= 2.0;
  }
  const double t = 1.0 - 0.17 * std::cos(radians(hMean - 30.0)) +
                   0.24 * std::cos(radians(2.0 * hMean)) +
                   0.32 * std::cos(radians(3.0 * hMean + 6.0)) -
                   0.20 * std::cos(radians(4.0 * hMean - 63.0));
  const double dTheta = 30.0 * std::exp(-std::pow((hMean - 275.0) / 25.0, 2.0));
  const double cpMean7 = std::pow(cpMean, 7.0);
  const double rC = 2.0 * std::sqrt(cpMean7 / (cpMean7 + kTwentyFiveToTheSeventh));
  const double l50 = (lMean - 50.0) * (lMean - 50.0);
  const double sL = unitLightnessWeight ? 1.0 : 1.0 + 0.015 * l50 / std::sqrt(20.0 + l50);
  const double sC = 1.0 + 0.045 * cpMean;
  const double sH = 1.0 + 0.015 * cpMean * t;
  const double rT = -std::sin(radians(2.0 * dTheta)) * rC;

  const double l = dL / sL, c = dC / sC, h = dH / sH;
  return std::sqrt(l * l + c * c + h * h + rT * c * h);
}

}  // namespace

double deltaE2000(const Lab& reference, const Lab& sample) {
  return ciede2000(reference, sample, false);
}

double deltaE2000UnitSL(const Lab& reference, const Lab& sample) {
  return ciede2000(reference, sample, true);
}

double deltaE76(const Lab& reference, const Lab& sample) {
  const double dL = sample.L - reference.L, da = sample.a - reference.a,
               db = sample.b - reference.b;
  return std::sqrt(dL * dL + da * da + db * db);
}

}  // namespace surrogate::colour
