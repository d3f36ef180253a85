#include "fit/basis.h"

#include <algorithm>
#include <cmath>

#include "core/error.h"

namespace surrogate::fit {

const char* basisName(Basis basis) {
  switch (basis) {
    case Basis::PtmLrgb: return "ptm-lrgb";
    case Basis::PtmRgb: return "ptm-rgb";
    case Basis::Hsh2: return "hsh2";
    case Basis::Hsh3: return "hsh3";
  }
  return "?";
}

Basis parseBasis(const std::string& name) {
  for (Basis b : {Basis::PtmLrgb, Basis::PtmRgb, Basis::Hsh2, Basis::Hsh3})
    if (name == basisName(b)) return b;
  throw Error(ErrorKind::Usage, "--basis", "fit",
              "unknown basis \"" + name + "\"; use ptm-lrgb, ptm-rgb, hsh2 or hsh3");
}

bool isPtm(Basis basis) { return basis == Basis::PtmLrgb || basis == Basis::PtmRgb; }

int basisTerms(Basis basis) {
  switch (basis) {
    case Basis::PtmLrgb:
    case Basis::PtmRgb: return 6;
    case Basis::Hsh2: return 4;
    case Basis::Hsh3: return 9;
  }
  return 0;
}

std::array<double, 6> ptmBasis(double lu, double lv) {
  return {lu * lu, lv * lv, lu * lv, lu, lv, 1.0};
}

void hshBasis(double lx, double ly, double lz, int terms, double* out) {
  const double norm = std::sqrt(lx * lx + ly * ly + lz * lz);
  const double z = norm > 0 ? std::clamp(lz / norm, -1.0, 1.0) : 1.0;
  const double theta = std::min(std::acos(z), kHshMaxTheta);
  const double phi = std::atan2(ly, lx);
  const double pi = M_PI;
  const double c = std::cos(theta);
  const double s = std::sqrt(c - c * c);
  const double t = 2 * c - 1;
  const double cp = std::cos(phi), sp = std::sin(phi);
  const double c2p = std::cos(2 * phi), s2p = std::sin(2 * phi);
  double h[16];
  h[0] = 1 / std::sqrt(2 * pi);
  h[1] = std::sqrt(6 / pi) * cp * s;
  h[2] = std::sqrt(3 / (2 * pi)) * t;
  h[3] = std::sqrt(6 / pi) * sp * s;
  h[4] = std::sqrt(30 / pi) * c2p * (c * c - c);
  h[5] = std::sqrt(30 / pi) * cp * t * s;
  h[6] = std::sqrt(5 / (2 * pi)) * (6 * c * c - 6 * c + 1);
  h[7] = std::sqrt(30 / pi) * sp * t * s;
  h[8] = std::sqrt(30 / pi) * s2p * (c * c - c);
  const double s3 = std::pow(c - c * c, 1.5);
  h[9] = 2 * std::sqrt(35 / pi) * std::cos(3 * phi) * s3;
  h[10] = std::sqrt(210 / pi) * c2p * t * (c * c - c);
  h[11] = 2 * std::sqrt(21 / pi) * cp * s * (5 * c * c - 5 * c + 1);
  h[12] = std::sqrt(7 / (2 * pi)) * (20 * c * c * c - 30 * c * c + 12 * c - 1);
  h[13] = 2 * std::sqrt(21 / pi) * sp * s * (5 * c * c - 5 * c + 1);
  h[14] = std::sqrt(210 / pi) * s2p * t * (c * c - c);
  h[15] = 2 * std::sqrt(35 / pi) * std::sin(3 * phi) * s3;
  for (int k = 0; k < terms && k < 16; ++k) out[k] = h[k];
}

}  // namespace surrogate::fit
