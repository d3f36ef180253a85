#include "fit/ptm_math.h"

namespace surrogate::fit {

double evaluatePtm(const PtmCoefficients& a, double lu, double lv) {
  return a[0] * lu * lu + a[1] * lv * lv + a[2] * lu * lv + a[3] * lu + a[4] * lv + a[5];
}

bool ptmMaximum(const PtmCoefficients& a, double* lu0, double* lv0) {
  const double d = 4 * a[0] * a[1] - a[2] * a[2];
  if (d == 0) {
    *lu0 = *lv0 = 0;
    return false;
  }
  *lu0 = (a[2] * a[4] - 2 * a[1] * a[3]) / d;
  *lv0 = (a[2] * a[3] - 2 * a[0] * a[4]) / d;
  return d > 0 && a[0] < 0;
}

PtmCoefficients applyDiffuseGain(const PtmCoefficients& a, double g, double lu0, double lv0) {
  PtmCoefficients b;
  b[0] = g * a[0];
  b[1] = g * a[1];
  b[2] = g * a[2];
  b[3] = (1 - g) * (2 * a[0] * lu0 + a[2] * lv0) + a[3];
  b[4] = (1 - g) * (2 * a[1] * lv0 + a[2] * lu0) + a[4];
  b[5] = (1 - g) * (a[0] * lu0 * lu0 + a[1] * lv0 * lv0 + a[2] * lu0 * lv0) +
         (a[3] - b[3]) * lu0 + (a[4] - b[4]) * lv0 + a[5];
  return b;
}

}  // namespace surrogate::fit
