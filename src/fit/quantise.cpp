#include "fit/quantise.h"

#include <algorithm>
#include <cmath>

namespace surrogate::fit {

PtmQuantisation choosePtmQuantisation(double lo, double hi) {
  lo = std::min(lo, 0.0);
  hi = std::max(hi, 0.0);
  PtmQuantisation q;
  const double range = hi - lo;
  if (!(range > 0) || !std::isfinite(range)) return q;  // all zero: scale 1, bias 0
  q.scale = std::max(range / 255.0, 1e-9);
  q.bias = static_cast<int>(std::clamp<long>(std::lround(-lo / q.scale), 0, 255));
  return q;
}

HshQuantisation chooseHshQuantisation(double lo, double hi) {
  HshQuantisation q;
  if (!std::isfinite(lo) || !std::isfinite(hi) || hi < lo) return q;
  q.bias = static_cast<float>(lo);
  q.scale = static_cast<float>(hi - lo);
  return q;
}

}  // namespace surrogate::fit
