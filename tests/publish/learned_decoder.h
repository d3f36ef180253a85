// Test support: an independent decoder of a learned web layout (type "rbf" or "bilinear",
// colour space "mrgb"), written from docs/formats.md ("Learned bases (rbf, bilinear) in the web
// layout") and from OpenLIME 1.2.6's published behaviour, sharing no code with src/: info.json
// read by webtest::JsonParser, the planes by OpenCV, the interpolation weights computed here
// in double precision. Used to check that what Surrogate writes is what a viewer draws.
//
//   learnedtest::Layout web = learnedtest::readLayout(dir);
//   std::vector<int> rgb = learnedtest::renderAt(web, {0.3, 0.2, 0.93});   // 8-bit, rows top-first
#pragma once

#include <algorithm>
#include <array>
#include <cmath>
#include <filesystem>
#include <string>
#include <vector>

#include <opencv2/core.hpp>
#include <opencv2/imgcodecs.hpp>

#include "web_reader.h"

namespace learnedtest {

struct Layout {
  bool rbf = false;
  int width = 0, height = 0, planes = 0, resolution = 0;
  std::vector<std::array<double, 3>> lights;
  std::vector<double> basis;          // decoded: (planes + 1) x nodes x 3
  std::vector<double> scale, bias;
  std::vector<std::vector<int>> rgb;  // per JPEG: R, G, B per texel, rows top-first
  int nodes() const { return rbf ? static_cast<int>(lights.size()) : resolution * resolution; }
};

inline Layout readLayout(const std::filesystem::path& dir) {
  const std::string text = webtest::slurp(dir / "info.json");
  const webtest::Json info = webtest::JsonParser(text).parseDocument();
  Layout l;
  l.rbf = info["type"].text == "rbf";
  l.width = static_cast<int>(info["width"].number);
  l.height = static_cast<int>(info["height"].number);
  l.planes = static_cast<int>(info["nplanes"].number);
  if (!l.rbf) l.resolution = static_cast<int>(info["resolution"].number);
  const std::vector<webtest::Json> none;
  const auto& lights = info.has("lights") ? info["lights"].items : none;  // for the record only in bilinear
  for (std::size_t i = 0; i + 2 < lights.size(); i += 3)
    l.lights.push_back({lights[i].number, lights[i + 1].number, lights[i + 2].number});
  const webtest::Json& m = info["materials"].items.at(0);
  for (int p = 0; p < l.planes; ++p) {
    l.scale.push_back(m["scale"].items.at(static_cast<std::size_t>(p)).number);
    l.bias.push_back(m["bias"].items.at(static_cast<std::size_t>(p)).number);
  }
  const auto& basis = info["basis"].items;
  const std::size_t perPlane = static_cast<std::size_t>(l.nodes()) * 3;
  if (basis.size() != (static_cast<std::size_t>(l.planes) + 1) * perPlane) throw std::runtime_error("basis length");
  for (std::size_t i = 0; i < basis.size(); ++i) {
    const std::size_t p = i / perPlane;
    l.basis.push_back(p == 0 ? basis[i].number / 255.0
                             : (basis[i].number - 127.0) / m["range"].items.at(p - 1).number);
  }
  for (int j = 0; j * 3 < l.planes; ++j) {
    const cv::Mat bgr = cv::imread((dir / ("plane_" + std::to_string(j) + ".jpg")).string(), cv::IMREAD_COLOR);
    if (bgr.cols != l.width || bgr.rows != l.height) throw std::runtime_error("plane size");
    std::vector<int> rgb;
    for (int y = 0; y < bgr.rows; ++y)
      for (int x = 0; x < bgr.cols; ++x)
        for (int c = 0; c < 3; ++c) rgb.push_back(bgr.at<cv::Vec3b>(y, x)[2 - c]);
    l.rgb.push_back(std::move(rgb));
  }
  return l;
}

// (node, weight) pairs at the unit light `d`.
inline std::vector<std::pair<int, double>> nodeWeights(const Layout& l, const std::array<double, 3>& d) {
  std::vector<std::pair<int, double>> w;
  if (l.rbf) {
    // Gaussian of the distance to each node, eps = 8 / (the distances' mean weighted by
    // exp(-2 d)), normalised to sum 1.
    std::vector<double> dist;
    double num = 0, den = 0;
    for (const auto& n : l.lights) {
      dist.push_back(std::hypot(d[0] - n[0], d[1] - n[1], d[2] - n[2]));
      num += dist.back() * std::exp(-2 * dist.back());
      den += std::exp(-2 * dist.back());
    }
    const double eps = 8 / (num / den);
    double sum = 0;
    for (std::size_t i = 0; i < dist.size(); ++i) {
      w.emplace_back(static_cast<int>(i), std::exp(-eps * dist[i] * dist[i]));
      sum += w.back().second;
    }
    for (auto& p : w) p.second /= sum;
    return w;
  }
  // The light's L1-normalised (x, y) turned by 45 degrees onto the square [-1, 1]^2, then onto
  // the R x R grid; the four nodes around it, bilinear weights; node (x, y) = x + y R.
  const double s = std::fabs(d[0]) + std::fabs(d[1]) + std::fabs(d[2]);
  const double gx = ((d[0] + d[1]) / s + 1) / 2 * (l.resolution - 1), gy = ((d[1] - d[0]) / s + 1) / 2 * (l.resolution - 1);
  const int sx = std::clamp(static_cast<int>(std::floor(gx)), 0, l.resolution - 2);
  const int sy = std::clamp(static_cast<int>(std::floor(gy)), 0, l.resolution - 2);
  const double fx = gx - sx, fy = gy - sy;
  w.emplace_back(sx + sy * l.resolution, (1 - fx) * (1 - fy));
  w.emplace_back(sx + 1 + sy * l.resolution, fx * (1 - fy));
  w.emplace_back(sx + (sy + 1) * l.resolution, (1 - fx) * fy);
  w.emplace_back(sx + 1 + (sy + 1) * l.resolution, fx * fy);
  return w;
}

// 8-bit R, G, B per texel at `light` (normalised here), as the viewer shows it.
inline std::vector<int> renderAt(const Layout& l, std::array<double, 3> light) {
  const double n = std::hypot(light[0], light[1], light[2]);
  for (double& v : light) v /= n;
  const auto nodes = nodeWeights(l, light);
  const std::size_t perPlane = static_cast<std::size_t>(l.nodes()) * 3;
  std::vector<double> W(static_cast<std::size_t>(l.planes + 1) * 3, 0);
  for (std::size_t p = 0; p <= static_cast<std::size_t>(l.planes); ++p)
    for (std::size_t k = 0; k < 3; ++k)
      for (const auto& [node, w] : nodes) W[p * 3 + k] += w * l.basis[p * perPlane + static_cast<std::size_t>(node) * 3 + k];
  std::vector<int> out;
  const std::size_t texels = static_cast<std::size_t>(l.width) * static_cast<std::size_t>(l.height);
  for (std::size_t t = 0; t < texels; ++t)
    for (std::size_t k = 0; k < 3; ++k) {
      double v = W[k];
      for (std::size_t p = 0; p < static_cast<std::size_t>(l.planes); ++p) {
        const double c = (l.rgb[p / 3][t * 3 + p % 3] / 255.0 - l.bias[p]) * l.scale[p];
        v += W[(p + 1) * 3 + k] * c;
      }
      out.push_back(static_cast<int>(std::lround(std::clamp(v, 0.0, 1.0) * 255)));
    }
  return out;
}

}  // namespace learnedtest
