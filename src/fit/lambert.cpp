#include "fit/lambert.h"

#include <cmath>
#include <vector>

#include "fit/pseudo_inverse.h"

namespace surrogate::fit {

namespace {
LambertDirections makeDirections() {
  LambertDirections d;
  for (int e = 15; e <= 75; e += 15) {
    const double el = e * M_PI / 180.0;
    for (int az = 0; az < 360; az += 30) {
      const double a = az * M_PI / 180.0;
      d.directions.push_back({std::cos(el) * std::cos(a), std::cos(el) * std::sin(a), std::sin(el)});
    }
  }
  d.directions.push_back({0.0, 0.0, 1.0});
  std::vector<double> m;
  for (const auto& v : d.directions) m.insert(m.end(), v.begin(), v.end());
  d.q = pseudoInverse(m, static_cast<int>(d.directions.size()), 3).matrix;
  return d;
}
}  // namespace

const LambertDirections& lambertDirections() {
  static const LambertDirections directions = makeDirections();  // thread-safe initialisation
  return directions;
}

std::vector<double> lambertOfBasis(const std::vector<double>& basisTable, int terms) {
  const LambertDirections& d = lambertDirections();
  const std::size_t k = d.directions.size();
  std::vector<double> out(3 * static_cast<std::size_t>(terms), 0.0);
  for (int r = 0; r < 3; ++r)
    for (int t = 0; t < terms; ++t)
      for (std::size_t j = 0; j < k; ++j) out[r * terms + t] += d.q[r * k + j] * basisTable[j * terms + t];
  return out;
}

bool normalFromLambert(const std::array<double, 3>& b, std::array<double, 3>* n) {
  const double len = std::sqrt(b[0] * b[0] + b[1] * b[1] + b[2] * b[2]);
  if (!(len > 1e-9) || !(b[2] > 0)) {
    *n = {0.0, 0.0, 1.0};
    return false;
  }
  *n = {b[0] / len, b[1] / len, b[2] / len};
  return true;
}

}  // namespace surrogate::fit
