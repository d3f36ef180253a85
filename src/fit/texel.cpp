#include "fit/texel.h"

#include "fit/basis.h"
#include "fit/lambert.h"

namespace surrogate::fit {

PtmCoefficients ptmChannel(const formats::PtmFile& ptm, int x, int y, int c) {
  const int channel = ptm.format == formats::PtmFile::Format::Lrgb ? 0 : c;
  PtmCoefficients a;
  for (int k = 0; k < 6; ++k) a[k] = ptm.coefficient(x, y, k, channel);
  return a;
}

PtmCoefficients ptmLuminance(const formats::PtmFile& ptm, int x, int y) {
  if (ptm.format == formats::PtmFile::Format::Lrgb) return ptmChannel(ptm, x, y, 0);
  PtmCoefficients a{};
  for (int c = 0; c < 3; ++c) {
    const PtmCoefficients ac = ptmChannel(ptm, x, y, c);
    for (int k = 0; k < 6; ++k) a[k] += ac[k] / 3.0;
  }
  return a;
}

namespace {
// Q B for the PTM polynomial: B's rows are (lu^2, lv^2, lu lv, lu, lv, 1) at each direction,
// the terms evaluatePtm multiplies a0..a5 by.
std::vector<double> makePtmLambert() {
  std::vector<double> table;
  for (const auto& d : lambertDirections().directions) {
    const double lu = d[0], lv = d[1];
    table.insert(table.end(), {lu * lu, lv * lv, lu * lv, lu, lv, 1.0});
  }
  return lambertOfBasis(table, 6);
}

// Q B for HSH with `terms` terms, B = 255 H_k at each direction (0..255 units).
std::vector<double> makeHshLambert(int terms) {
  std::vector<double> table;
  double h[16];
  for (const auto& d : lambertDirections().directions) {
    hshBasis(d[0], d[1], d[2], terms, h);
    for (int t = 0; t < terms; ++t) table.push_back(255.0 * h[t]);
  }
  return lambertOfBasis(table, terms);
}

const std::vector<double>& hshLambertMatrix(int terms) {
  static const std::vector<double> m4 = makeHshLambert(4), m9 = makeHshLambert(9), m16 = makeHshLambert(16);
  return terms == 4 ? m4 : terms == 9 ? m9 : m16;
}
}  // namespace

std::array<double, 3> ptmLambert(const PtmCoefficients& a) {
  static const std::vector<double> m = makePtmLambert();  // thread-safe initialisation
  std::array<double, 3> b{0, 0, 0};
  for (int r = 0; r < 3; ++r)
    for (int k = 0; k < 6; ++k) b[r] += m[r * 6 + k] * a[k];
  return b;
}

void hshLambert(const formats::HshFile& hsh, int x, int y, std::array<double, 3> b[3]) {
  const std::vector<double>& m = hshLambertMatrix(hsh.terms);
  for (int c = 0; c < 3; ++c) {
    double coef[16];
    for (int t = 0; t < hsh.terms; ++t) coef[t] = hsh.coefficient(x, y, c, t);
    for (int r = 0; r < 3; ++r) {
      double v = 0;
      for (int t = 0; t < hsh.terms; ++t) v += m[r * hsh.terms + t] * coef[t];
      b[c][r] = v;
    }
  }
}

}  // namespace surrogate::fit
