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
std::vector<double> makeHshTable(int terms) {
  std::vector<double> table;
  double h[16];
  for (const auto& d : lambertDirections().directions) {
    hshBasis(d[0], d[1], d[2], terms, h);
    table.insert(table.end(), h, h + terms);
  }
  return table;
}
}  // namespace

const std::vector<double>& hshAtLambertDirections(int terms) {
  static const std::vector<double> t4 = makeHshTable(4), t9 = makeHshTable(9),
                                   t16 = makeHshTable(16);
  return terms == 4 ? t4 : terms == 9 ? t9 : t16;
}

void hshLambert(const formats::HshFile& hsh, int x, int y, std::array<double, 3> b[3]) {
  const std::vector<double>& table = hshAtLambertDirections(hsh.terms);
  const std::size_t k = lambertDirections().directions.size();
  std::vector<double> values(k);
  for (int c = 0; c < 3; ++c) {
    double coef[16];
    for (int t = 0; t < hsh.terms; ++t) coef[t] = hsh.coefficient(x, y, c, t);
    for (std::size_t j = 0; j < k; ++j) {
      double v = 0;
      for (int t = 0; t < hsh.terms; ++t) v += coef[t] * table[j * hsh.terms + t];
      values[j] = 255.0 * v;
    }
    b[c] = lambertFit(values.data());
  }
}

}  // namespace surrogate::fit
