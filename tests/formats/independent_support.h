// What the golden-file tests share (test_independent_reader.cpp, test_independent_known.cpp,
// test_independent_fitted.cpp): files read and written whole, the lights they render at, files
// of known coefficients, an unquantised least-squares fit and a scene no PTM or HSH reproduces
// exactly. Built on the independent format code (independent_format.h), not on src/formats.
#pragma once

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <filesystem>
#include <string>
#include <vector>

#include "core/image.h"
#include "core/stack.h"
#include "independent_format.h"

namespace golden {

using Light = std::array<double, 3>;

// Lights for rendering: overhead, every quadrant, from the image's top and right edges,
// grazing, and unnormalised vectors.
inline const std::vector<Light> kRenderLights = {{0, 0, 1},        {0.5, 0.3, 0.81},  {-0.7, 0.2, 0.5},
                                                 {0.1, -0.8, 0.6}, {-0.4, -0.5, 0.77}, {0, 1, 0.25},
                                                 {1, 0, 0.25},     {1, 2, 2},          {0.97, -0.2, 0.1}};

std::string slurp(const std::filesystem::path& p);

void spit(const std::filesystem::path& p, const std::string& bytes);

// N lights over elevations 20..80 degrees and all azimuths (golden-angle spiral).
std::vector<Light> captureLights(int n);

// The nearest 8-bit value of a closed-form value: |got - clamp(v)| <= 0.5 (plus float noise).
void checkNearest(double got, double value, const std::string& where);

indep::Ptm knownPtm(bool lrgb, int w, int h);

indep::Rti knownRti(int terms, int w, int h);

// Unquantised least-squares coefficients (normal equations) of samples s_i over rows w(l_i).
std::vector<double> leastSquares(const std::vector<std::vector<double>>& rows,
                                 const std::vector<double>& s);

// How far quantisation alone can move a rendered value: half a step of every coefficient times
// the largest |w_k| over the lights, in 0..255 units (`step` in the rendered units).
double quantisationBound(const std::vector<std::vector<double>>& rows, const std::vector<double>& step);

double psnr(double sumSq, std::size_t count);

// Surrogate's rendered 8-bit value (render() widens 8-bit values by 257).
double rendered(const surrogate::Image& im, int x, int y, int c);

// A scene no PTM or HSH reproduces exactly: a Lambertian surface with ambient light and a
// Blinn-Phong highlight; the normal tilts with the column and, strongly, with the row (so
// that a flipped row order shows), the albedo differs per channel.
struct Scene {
  int w = 13, h = 9;
  std::array<double, 3> normal(int x, int y) const {
    const double nx = 0.45 * std::sin(0.7 * x - 2.0);
    const double ny = 0.6 * (2.0 * y / (h - 1) - 1.0);
    return {nx, ny, std::sqrt(1 - nx * nx - ny * ny)};
  }
  double albedo(int x, int y, int c) const { return 0.35 + 0.1 * c + 0.03 * ((x + 2 * y) % 5); }
  double value(int x, int y, int c, const Light& l) const {  // 0..255 units
    const auto n = normal(x, y);
    const double len = std::sqrt(l[0] * l[0] + l[1] * l[1] + l[2] * l[2]);
    const double lx = l[0] / len, ly = l[1] / len, lz = l[2] / len;
    const double ndotl = std::max(0.0, n[0] * lx + n[1] * ly + n[2] * lz);
    double hv[3] = {lx, ly, lz + 1};
    const double hl = std::sqrt(hv[0] * hv[0] + hv[1] * hv[1] + hv[2] * hv[2]);
    const double ndoth = std::max(0.0, (n[0] * hv[0] + n[1] * hv[1] + n[2] * hv[2]) / hl);
    return std::min(255.0, 255.0 * albedo(x, y, c) * (0.2 + 0.9 * ndotl) + 25.0 * std::pow(ndoth, 12));
  }
  // The photographs as 16-bit samples (the Image convention), and the same in 0..255 units.
  surrogate::MemoryImageStack photographs(const std::vector<Light>& lights,
                                          std::vector<std::vector<double>>* units) const {
    std::vector<surrogate::Image> images;
    units->clear();
    for (const Light& l : lights) {
      surrogate::Image im(w, h, 3);
      std::vector<double> u(static_cast<std::size_t>(w) * h * 3);
      for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x)
          for (int c = 0; c < 3; ++c) {
            const auto s = static_cast<std::uint16_t>(std::lround(value(x, y, c, l) * 257.0));
            im.at(x, y, c) = s;
            u[(static_cast<std::size_t>(y) * w + x) * 3 + c] = s / 257.0;
          }
      images.push_back(std::move(im));
      units->push_back(std::move(u));
    }
    return surrogate::MemoryImageStack(std::move(images));
  }
};

}  // namespace golden
