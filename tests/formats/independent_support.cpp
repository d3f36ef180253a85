// The golden-file tests' shared helpers (independent_support.h).
#include "independent_support.h"

#include <catch2/catch.hpp>

#include <fstream>
#include <sstream>

#include "../fit/reference_basis.h"

namespace fs = std::filesystem;
namespace ref = surrogate::reference;
using surrogate::Image;

namespace golden {

namespace {

// A deterministic byte in [lo, hi] that differs between neighbouring texels, rows, channels
// and terms.
std::uint8_t pattern(int x, int y, int c, int k, int lo, int hi) {
  const unsigned h = static_cast<unsigned>(x * 7919 + y * 104729 + c * 1299709 + k * 15485863 +
                                           x * y * 31 + 17);
  return static_cast<std::uint8_t>(lo + (h ^ (h >> 7)) % static_cast<unsigned>(hi - lo + 1));
}

// Gaussian elimination with partial pivoting: solves m x = b (n x n), m and b overwritten.
std::vector<double> solve(std::vector<double> m, std::vector<double> b, int n) {
  for (int i = 0; i < n; ++i) {
    int best = i;
    for (int r = i + 1; r < n; ++r)
      if (std::fabs(m[r * n + i]) > std::fabs(m[best * n + i])) best = r;
    for (int j = 0; j < n; ++j) std::swap(m[i * n + j], m[best * n + j]);
    std::swap(b[i], b[best]);
    for (int r = i + 1; r < n; ++r) {
      const double f = m[r * n + i] / m[i * n + i];
      for (int j = i; j < n; ++j) m[r * n + j] -= f * m[i * n + j];
      b[r] -= f * b[i];
    }
  }
  std::vector<double> x(n);
  for (int i = n - 1; i >= 0; --i) {
    double s = b[i];
    for (int j = i + 1; j < n; ++j) s -= m[i * n + j] * x[j];
    x[i] = s / m[i * n + i];
  }
  return x;
}

}  // namespace

std::string slurp(const fs::path& p) {
  std::ifstream in(p, std::ios::binary);
  std::ostringstream s;
  s << in.rdbuf();
  return s.str();
}

void spit(const fs::path& p, const std::string& bytes) {
  std::ofstream out(p, std::ios::binary);
  out.write(bytes.data(), static_cast<std::streamsize>(bytes.size()));
}

std::vector<Light> captureLights(int n) {
  std::vector<Light> out;
  for (int i = 0; i < n; ++i) {
    const double el = (20.0 + 60.0 * (i + 0.5) / n) * ref::kPi / 180.0, az = i * 2.399963229728653;
    out.push_back({std::cos(el) * std::cos(az), std::cos(el) * std::sin(az), std::sin(el)});
  }
  return out;
}

double rendered(const Image& im, int x, int y, int c) { return im.at(x, y, c) / 257.0; }

void checkNearest(double got, double value, const std::string& where) {
  const double want = std::min(255.0, std::max(0.0, value));
  INFO(where << ": Surrogate " << got << ", closed form " << value);
  CHECK(std::fabs(got - want) <= 0.5 + 1e-6);
}

indep::Ptm knownPtm(bool lrgb, int w, int h) {
  indep::Ptm p;
  p.lrgb = lrgb;
  p.width = w;
  p.height = h;
  p.scale = {0.25, 0.25, 0.125, 0.5, 0.5, 1.0};
  p.bias = {200, 200, 128, 128, 128, 0};
  p.allocate();
  //                 a0 in [-20, 0]  a1 in [-20, 0]  a2 in [-8, 8]  a3, a4 in [-20, 20]  a5 in [120, 230]
  const int lo[6] = {120, 120, 64, 88, 88, 120}, hi[6] = {200, 200, 192, 168, 168, 230};
  for (std::size_t c = 0; c < p.coef.size(); ++c)
    for (int y = 0; y < h; ++y)
      for (int x = 0; x < w; ++x)
        for (int k = 0; k < 6; ++k) p.coef[c][y][x][k] = pattern(x, y, static_cast<int>(c), k, lo[k], hi[k]);
  for (int y = 0; y < static_cast<int>(p.colour.size()); ++y)
    for (int x = 0; x < w; ++x)
      for (int c = 0; c < 3; ++c) p.colour[y][x][c] = pattern(x, y, c, 7, 40, 230);
  return p;
}

indep::Rti knownRti(int terms, int w, int h) {
  indep::Rti r;
  r.width = w;
  r.height = h;
  r.terms = terms;
  for (int k = 0; k < terms; ++k) {
    r.scale.push_back(k == 0 ? 1.0f : 0.25f);   // H0's coefficient in [0.5, 1.5]
    r.bias.push_back(k == 0 ? 0.5f : -0.125f);  // the others in [-0.125, 0.125]
  }
  r.allocate();
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x)
      for (int c = 0; c < 3; ++c)
        for (int k = 0; k < terms; ++k) r.coef[y][x][c][k] = pattern(x, y, c, k, 0, 255);
  return r;
}

std::vector<double> leastSquares(const std::vector<std::vector<double>>& rows,
                                 const std::vector<double>& s) {
  const int t = static_cast<int>(rows[0].size());
  std::vector<double> ata(t * t, 0.0), atb(t, 0.0);
  for (std::size_t i = 0; i < rows.size(); ++i)
    for (int a = 0; a < t; ++a) {
      atb[a] += rows[i][a] * s[i];
      for (int b = 0; b < t; ++b) ata[a * t + b] += rows[i][a] * rows[i][b];
    }
  return solve(ata, atb, t);
}

double quantisationBound(const std::vector<std::vector<double>>& rows, const std::vector<double>& step) {
  double bound = 0;
  for (std::size_t k = 0; k < step.size(); ++k) {
    double largest = 0;
    for (const auto& r : rows) largest = std::max(largest, std::fabs(r[k]));
    bound += step[k] / 2 * largest;
  }
  return bound + 1e-6;
}

double psnr(double sumSq, std::size_t count) {
  return 20 * std::log10(255.0 / std::sqrt(sumSq / static_cast<double>(count)));
}

}  // namespace golden
