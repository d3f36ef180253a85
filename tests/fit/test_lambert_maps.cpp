// Normals and albedo of HSH and PTM files against a Lambertian fit written out here from its
// definition (src/fit/lambert.h): the model evaluated at 61 fixed directions (elevations 15 to
// 75 degrees in steps of 15 by 12 azimuths, plus the zenith), b = the least-squares solution of
// I(l) = b . l through them (3 x 3 normal equations), normal b / |b| of the mean of the
// channels' b; the albedo is each channel's model evaluated at that normal (for a PTM, at the
// maximum of the luminance polynomial, written out here from the closed form). The basis comes
// from reference_basis.h, not from src/fit.
#include <catch2/catch.hpp>

#include <array>
#include <cmath>
#include <random>
#include <vector>

#include "fit/normals.h"
#include "formats/ptm.h"
#include "formats/rti_hsh.h"
#include "reference_basis.h"

using namespace surrogate;
namespace ref = surrogate::reference;

namespace {

std::vector<std::array<double, 3>> directions() {
  std::vector<std::array<double, 3>> d;
  for (int e = 15; e <= 75; e += 15)
    for (int a = 0; a < 360; a += 30) {
      const double el = e * M_PI / 180, az = a * M_PI / 180;
      d.push_back({std::cos(el) * std::cos(az), std::cos(el) * std::sin(az), std::sin(el)});
    }
  d.push_back({0, 0, 1});
  return d;
}

// Least squares b with values[j] ~= b . d_j, by the normal equations and Cramer's rule.
std::array<double, 3> lambertReference(const std::vector<double>& values) {
  const auto d = directions();
  double m[3][3] = {}, r[3] = {};
  for (std::size_t j = 0; j < d.size(); ++j)
    for (int a = 0; a < 3; ++a) {
      r[a] += d[j][a] * values[j];
      for (int b = 0; b < 3; ++b) m[a][b] += d[j][a] * d[j][b];
    }
  auto det = [](double a[3][3]) {
    return a[0][0] * (a[1][1] * a[2][2] - a[1][2] * a[2][1]) - a[0][1] * (a[1][0] * a[2][2] - a[1][2] * a[2][0]) +
           a[0][2] * (a[1][0] * a[2][1] - a[1][1] * a[2][0]);
  };
  const double whole = det(m);
  std::array<double, 3> b{};
  for (int c = 0; c < 3; ++c) {
    double k[3][3];
    for (int a = 0; a < 3; ++a)
      for (int e = 0; e < 3; ++e) k[a][e] = e == c ? r[a] : m[a][e];
    b[c] = det(k) / whole;
  }
  return b;
}

double length(const std::array<double, 3>& b) { return std::sqrt(b[0] * b[0] + b[1] * b[1] + b[2] * b[2]); }

int albedoLevel(double rho) { return static_cast<int>(std::lround(std::clamp(rho, 0.0, 255.0))); }

// The encoded normal (16-bit levels) of the mean b, or (0, 0, 1) when it faces away.
std::array<int, 3> normalLevels(const std::array<double, 3>& b) {
  const double len = length(b);
  const std::array<double, 3> n = len > 1e-9 && b[2] > 0 ? std::array<double, 3>{b[0] / len, b[1] / len, b[2] / len}
                                                         : std::array<double, 3>{0, 0, 1};
  std::array<int, 3> out{};
  for (int c = 0; c < 3; ++c) out[c] = static_cast<int>(std::lround((n[c] + 1) / 2 * 65535));
  return out;
}

// The unit normal of b, or (0, 0, 1) when it faces away (as normalLevels encodes it).
std::array<double, 3> unitNormal(const std::array<double, 3>& b) {
  const double len = length(b);
  return len > 1e-9 && b[2] > 0 ? std::array<double, 3>{b[0] / len, b[1] / len, b[2] / len}
                                : std::array<double, 3>{0, 0, 1};
}

}  // namespace

TEST_CASE("lambert maps: HSH normals are the least-squares Lambertian fit at 61 directions and albedo the model there") {
  std::mt19937 random(5);
  std::uniform_int_distribution<int> byte(0, 255);
  const auto d = directions();
  for (int terms : {4, 9, 16}) {
    INFO("terms " << terms);
    formats::HshFile hsh;
    hsh.width = 5;
    hsh.height = 4;
    hsh.terms = terms;
    for (int t = 0; t < terms; ++t) {
      hsh.scale.push_back(t == 0 ? 2.0f : 0.6f / (1 + t));
      hsh.bias.push_back(t == 0 ? 0.2f : -0.3f / (1 + t));
    }
    for (std::size_t i = 0; i < hsh.texels() * 3 * terms; ++i) hsh.coefficients.push_back(byte(random));
    const Image normals = fit::normalMap(hsh);
    const Image albedo = fit::albedoMap(hsh);
    for (int y = 0; y < hsh.height; ++y)
      for (int x = 0; x < hsh.width; ++x) {
        std::array<double, 3> mean{};
        for (int c = 0; c < 3; ++c) {
          std::vector<double> values;
          for (const auto& l : d) {
            double v = 0;
            for (int t = 0; t < terms; ++t) v += hsh.coefficient(x, y, c, t) * ref::hshTerm(t, l[0], l[1], l[2]);
            values.push_back(255 * v);
          }
          const auto b = lambertReference(values);
          for (int r = 0; r < 3; ++r) mean[r] += b[r] / 3;
        }
        const auto want = normalLevels(mean);
        for (int c = 0; c < 3; ++c) CHECK(std::abs(int(normals.at(x, y, c)) - want[c]) <= 1);
        const auto n = unitNormal(mean);
        for (int c = 0; c < 3; ++c) {
          double v = 0;
          for (int t = 0; t < terms; ++t) v += hsh.coefficient(x, y, c, t) * ref::hshTerm(t, n[0], n[1], n[2]);
          CHECK(std::abs(albedo.at(x, y, c) / 257 - albedoLevel(255 * v)) <= 1);
        }
      }
  }
}

TEST_CASE("lambert maps: RGB PTM albedo is each channel at the maximum of the luminance polynomial") {
  std::mt19937 random(9);
  std::uniform_int_distribution<int> byte(0, 255);
  formats::PtmFile ptm;
  ptm.format = formats::PtmFile::Format::Rgb;
  ptm.width = 6;
  ptm.height = 3;
  ptm.scale = {0.9, 0.8, 0.7, 1.1, 1.2, 1.5};
  ptm.bias = {128, 120, 130, 100, 110, 20};
  for (std::size_t i = 0; i < ptm.texels() * 18; ++i) ptm.coefficients.push_back(byte(random));
  const Image albedo = fit::albedoMap(ptm);
  int maxima = 0, fallbacks = 0;
  for (int y = 0; y < ptm.height; ++y)
    for (int x = 0; x < ptm.width; ++x) {
      // The luminance polynomial (the channels' mean) and its maximum (docs/hrti-math.md).
      double a[6] = {};
      for (int k = 0; k < 6; ++k)
        for (int c = 0; c < 3; ++c) a[k] += ptm.coefficient(x, y, k, c) / 3;
      const double d = 4 * a[0] * a[1] - a[2] * a[2];
      double lu = 0, lv = 0;
      if (d > 0 && a[0] < 0) {
        ++maxima;
        lu = (a[2] * a[4] - 2 * a[1] * a[3]) / d;
        lv = (a[2] * a[3] - 2 * a[0] * a[4]) / d;
        const double r = std::hypot(lu, lv);
        if (r > 1) lu /= r, lv /= r;
      } else {
        ++fallbacks;
        std::vector<double> values;
        for (const auto& l : directions()) {
          const auto uv = ref::ptmArguments(l[0], l[1], l[2]);
          double v = 0;
          for (int k = 0; k < 6; ++k) v += a[k] * ref::ptmTerm(k, uv[0], uv[1]);
          values.push_back(v);
        }
        const auto n = unitNormal(lambertReference(values));
        lu = n[0], lv = n[1];
      }
      for (int c = 0; c < 3; ++c) {
        double v = 0;
        for (int k = 0; k < 6; ++k) v += ptm.coefficient(x, y, k, c) * ref::ptmTerm(k, lu, lv);
        CHECK(std::abs(albedo.at(x, y, c) / 257 - albedoLevel(v)) <= 1);
      }
    }
  // Random coefficients give both kinds of texel, so both paths are checked.
  CHECK(maxima > 0);
  CHECK(fallbacks > 0);
}
