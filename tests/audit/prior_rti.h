// Test support: "someone else's RTI", made without src/fit or src/formats. Lambertian
// photographs of a bumpy coloured surface, a least-squares PTM LRGB fit of them, and a
// PTM_1.2 LRGB writer, all from the published description (docs/formats.md, ".ptm" and
// "LRGB: colour and luminance"; docs/hrti-math.md, "The PTM basis").
#pragma once

#include <Eigen/Dense>
#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <fstream>
#include <iomanip>
#include <sstream>
#include <string>
#include <vector>

#include "core/image.h"
#include "../light_spiral.h"

namespace surrogate::test {

using Light = std::array<double, 3>;

// N lights at elevations 40..75 degrees, all azimuths (golden-angle spiral): none grazing, so a
// Lambertian surface is lit everywhere and a biquadratic in (lx, ly) fits it closely.
inline std::vector<Light> auditLights(int n) { return spiralLights(n, 40.0, 75.0); }

// `l` tilted by `degrees` towards the viewing axis' opposite (its elevation raised): the
// angle between the two unit vectors is exactly `degrees`.
inline Light tilted(const Light& l, double degrees) {
  const double el = std::asin(l[2]) + degrees * M_PI / 180.0;
  const double az = std::atan2(l[1], l[0]);
  return {std::cos(el) * std::cos(az), std::cos(el) * std::sin(az), std::sin(el)};
}

// The surface: normals tilted up to about 20 degrees, albedo varying per channel.
struct Surface {
  int w, h;
  std::array<double, 3> normal(int x, int y) const {
    const double gx = 0.3 * std::cos(0.37 * x + 0.11 * y), gy = 0.25 * std::sin(0.29 * y - 0.07 * x);
    const double n = std::sqrt(gx * gx + gy * gy + 1);
    return {-gx / n, -gy / n, 1 / n};
  }
  std::array<double, 3> albedo(int x, int y) const {
    return {0.55 + 0.1 * std::sin(0.2 * x), 0.45 + 0.1 * std::cos(0.15 * y), 0.35 + 0.05 * std::sin(0.1 * (x + y))};
  }
};

// The photographs as another tool's processing left them: each value v (0..255) becomes
// 255 (v / 255)^gamma.
inline std::vector<Image> withGamma(std::vector<Image> photos, double gamma) {
  for (Image& im : photos)
    for (auto& v : im.pixels) v = static_cast<std::uint16_t>(std::lround(255.0 * std::pow(v / 65535.0, gamma)) * 257);
  return photos;
}

// 16-bit RGB photographs: value = 255 albedo (n . l) in 0..255 units, rounded like an 8-bit
// export widened *257.
inline std::vector<Image> lambertPhotos(const Surface& s, const std::vector<Light>& lights) {
  std::vector<Image> out;
  for (const Light& l : lights) {
    Image im(s.w, s.h, 3);
    for (int y = 0; y < s.h; ++y)
      for (int x = 0; x < s.w; ++x) {
        const auto n = s.normal(x, y);
        const auto a = s.albedo(x, y);
        const double shade = std::max(0.0, n[0] * l[0] + n[1] * l[1] + n[2] * l[2]);
        for (int c = 0; c < 3; ++c)
          im.at(x, y, c) = static_cast<std::uint16_t>(std::lround(std::clamp(255 * a[c] * shade, 0.0, 255.0)) * 257);
      }
    out.push_back(std::move(im));
  }
  return out;
}

// A PTM LRGB as fitted by "another tool": colour = the plain mean over the photographs
// (uniform weights, unlike Surrogate's), L_i = 255 (R+G+B) / (C_R+C_G+C_B), and a0..a5 the
// least-squares fit of L_i in w = (lu^2, lv^2, lu lv, lu, lv, 1).
struct PriorPtm {
  int w = 0, h = 0;
  std::vector<std::array<double, 6>> a;          // per texel, rows top first
  std::vector<std::array<std::uint8_t, 3>> rgb;  // per texel
};

inline PriorPtm fitPrior(const std::vector<Image>& photos, const std::vector<Light>& lights) {
  const int n = static_cast<int>(photos.size());
  Eigen::MatrixXd A(n, 6);
  for (int i = 0; i < n; ++i) {
    const double lu = lights[i][0], lv = lights[i][1];
    A.row(i) << lu * lu, lv * lv, lu * lv, lu, lv, 1;
  }
  const auto qr = A.colPivHouseholderQr();
  PriorPtm p;
  p.w = photos[0].width, p.h = photos[0].height;
  for (int y = 0; y < p.h; ++y)
    for (int x = 0; x < p.w; ++x) {
      std::array<std::uint8_t, 3> colour{};
      for (int c = 0; c < 3; ++c) {
        double sum = 0;
        for (const Image& im : photos) sum += im.at(x, y, c) / 257.0;
        colour[c] = static_cast<std::uint8_t>(std::clamp<long>(std::lround(sum / n), 1, 255));
      }
      const double chroma = colour[0] + colour[1] + colour[2];
      Eigen::VectorXd L(n);
      for (int i = 0; i < n; ++i)
        L(i) = 255.0 * (photos[i].at(x, y, 0) + photos[i].at(x, y, 1) + photos[i].at(x, y, 2)) / 257.0 / chroma;
      const Eigen::VectorXd a = qr.solve(L);
      p.a.push_back({a(0), a(1), a(2), a(3), a(4), a(5)});
      p.rgb.push_back(colour);
    }
  return p;
}

// How the writer chooses each plane's scale s and bias b (decoding: a = (byte - b) * s).
enum class BiasRule {
  WithZero,     // the range widened to include 0, so b always fits 0..255 (docs/formats.md)
  ClampedBias,  // the range as it is, b = round(-lo / s) clamped to 0..255: a plane whose
                // values are all positive (or all negative) gets a bias that cannot hold them
  NarrowRange,  // WithZero over the central 90% of each plane's values only: the 5% at each
                // end are clipped to byte 0 or 255
};

// The value with a share q of the plane's values below it.
inline double planeQuantile(const PriorPtm& p, int k, double q) {
  std::vector<double> v;
  for (const auto& a : p.a) v.push_back(a[k]);
  std::sort(v.begin(), v.end());
  return v[static_cast<std::size_t>(q * (v.size() - 1))];
}

inline std::string ptmText(const PriorPtm& p, BiasRule rule) {
  std::array<double, 6> scale{};
  std::array<int, 6> bias{};
  for (int k = 0; k < 6; ++k) {
    double lo = p.a[0][k], hi = p.a[0][k];
    for (const auto& a : p.a) lo = std::min(lo, a[k]), hi = std::max(hi, a[k]);
    if (rule == BiasRule::NarrowRange) lo = planeQuantile(p, k, 0.05), hi = planeQuantile(p, k, 0.95);
    if (rule != BiasRule::ClampedBias) lo = std::min(lo, 0.0), hi = std::max(hi, 0.0);
    scale[k] = hi > lo ? (hi - lo) / 255.0 : 1.0;
    bias[k] = static_cast<int>(std::clamp<long>(std::lround(-lo / scale[k]), 0, 255));
  }
  std::ostringstream out;
  out << "PTM_1.2\nPTM_FORMAT_LRGB\n" << p.w << "\n" << p.h << "\n";
  out << std::fixed << std::setprecision(10);
  for (int k = 0; k < 6; ++k) out << scale[k] << (k < 5 ? " " : "\n");
  for (int k = 0; k < 6; ++k) out << bias[k] << (k < 5 ? " " : "\n");
  std::string payload;
  for (int y = p.h - 1; y >= 0; --y)  // bottom row first
    for (int x = 0; x < p.w; ++x)
      for (int k = 0; k < 6; ++k) {
        const double byte = std::lround(p.a[y * p.w + x][k] / scale[k] + bias[k]);
        payload += static_cast<char>(static_cast<std::uint8_t>(std::clamp(byte, 0.0, 255.0)));
      }
  for (int y = p.h - 1; y >= 0; --y)
    for (int x = 0; x < p.w; ++x)
      for (int c = 0; c < 3; ++c) payload += static_cast<char>(p.rgb[y * p.w + x][c]);
  return out.str() + payload;
}

inline void writeText(const std::string& path, const std::string& text) {
  std::ofstream(path, std::ios::binary) << text;
}

}  // namespace surrogate::test
