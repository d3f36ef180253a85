// Quality at lights a model never saw (fit/held_out.h): PSNR and SSIM of a relit image against
// the photograph left out, which photographs to leave out, and the nearest-photograph baseline.
#include "fit/held_out.h"

#include <algorithm>
#include <cmath>
#include <numeric>
#include <string>

#include <opencv2/core.hpp>
#include <opencv2/quality/qualityssim.hpp>

#include "core/error.h"

namespace surrogate::fit {
namespace {

constexpr const char* kStep = "held-out lights";

// The unit vector of `v`, or an error naming `what` when it has no direction.
std::array<double, 3> unit(const std::array<double, 3>& v, ErrorKind kind, const std::string& what) {
  double norm = std::sqrt(v[0] * v[0] + v[1] * v[1] + v[2] * v[2]);
  if (!(norm > 1e-12) || !std::isfinite(norm))
    throw Error(kind, what, kStep, "a light must be a non-zero direction x,y,z");
  return {v[0] / norm, v[1] / norm, v[2] / norm};
}

// Angle between two unit vectors, in radians; acos's argument clamped against rounding.
double angleBetween(const std::array<double, 3>& a, const std::array<double, 3>& b) {
  double dot = a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
  return std::acos(std::clamp(dot, -1.0, 1.0));
}

std::vector<std::array<double, 3>> unitLights(const std::vector<std::array<double, 3>>& lights,
                                              ErrorKind kind, const std::string& what) {
  std::vector<std::array<double, 3>> out;
  out.reserve(lights.size());
  for (const auto& l : lights) out.push_back(unit(l, kind, what));
  return out;
}

// One image as a float matrix in 8-bit units (value / 257): what both metrics measure.
cv::Mat asEightBitUnits(const Image& image) {
  cv::Mat out(image.height, image.width, CV_MAKETYPE(CV_32F, image.channels));
  const std::uint16_t* in = image.pixels.data();
  for (int y = 0; y < image.height; ++y) {
    float* row = out.ptr<float>(y);
    for (int i = 0; i < image.width * image.channels; ++i) row[i] = static_cast<float>(*in++ / 257.0);
  }
  return out;
}

}  // namespace

HeldOutScore compareImages(const Image& rendered, const Image& photograph) {
  if (rendered.width != photograph.width || rendered.height != photograph.height ||
      rendered.channels != photograph.channels || rendered.empty() ||
      rendered.pixels.size() != photograph.pixels.size())
    throw Error(ErrorKind::Internal, "", kStep,
                "the relit image and the photograph differ in size or channels (" +
                    std::to_string(rendered.width) + "x" + std::to_string(rendered.height) + "x" +
                    std::to_string(rendered.channels) + " against " + std::to_string(photograph.width) +
                    "x" + std::to_string(photograph.height) + "x" + std::to_string(photograph.channels) + ")");
  HeldOutScore score;
  // Sum of squares in double over integers: exact for any image size Surrogate meets.
  double sum = 0;
  for (std::size_t i = 0; i < rendered.pixels.size(); ++i) {
    double d = (static_cast<double>(rendered.pixels[i]) - photograph.pixels[i]) / 257.0;
    sum += d * d;
  }
  score.mse = sum / static_cast<double>(rendered.pixels.size());
  score.psnr = score.mse > 0 ? std::min(100.0, 10 * std::log10(255.0 * 255.0 / score.mse)) : 100.0;

  // OpenCV's QualitySSIM is Wang et al.'s index with their constants (11x11 Gaussian window,
  // sigma 1.5, C1 = (0.01 L)^2, C2 = (0.03 L)^2, L = 255), so the images go in 8-bit units; its
  // window reflects at the borders where Wang's reference code drops them (a difference of a
  // 5-pixel rim). It gives each channel's mean; the figure is their mean.
  cv::Mat map;
  cv::Scalar perChannel =
      cv::quality::QualitySSIM::compute(asEightBitUnits(rendered), asEightBitUnits(photograph), map);
  double ssim = 0;
  for (int c = 0; c < rendered.channels; ++c) ssim += perChannel[c];
  score.ssim = ssim / rendered.channels;
  return score;
}

HeldOutScore meanScore(const std::vector<HeldOutScore>& scores) {
  if (scores.empty())
    throw Error(ErrorKind::Internal, "", kStep, "no held-out images to pool");
  HeldOutScore out;
  for (const auto& s : scores) {
    out.mse += s.mse;
    out.ssim += s.ssim;
  }
  out.mse /= static_cast<double>(scores.size());
  out.ssim /= static_cast<double>(scores.size());
  out.psnr = out.mse > 0 ? std::min(100.0, 10 * std::log10(255.0 * 255.0 / out.mse)) : 100.0;
  return out;
}

std::vector<int> chooseHeldOut(const std::vector<std::array<double, 3>>& lights, int count) {
  const int n = static_cast<int>(lights.size());
  if (count <= 0 || count >= n)
    throw Error(ErrorKind::Usage, "--holdout", kStep,
                "leave out at least 1 and fewer than the " + std::to_string(n) +
                    " photographs (asked for " + std::to_string(count) + ")");
  auto unitL = unitLights(lights, ErrorKind::Input, "lights");
  // Angles equal up to rounding count as ties, so that a symmetric dome gives the lower index
  // whatever the last bit of its coordinates.
  constexpr double kTie = 1e-9;

  std::array<double, 3> mean{0, 0, 0};
  for (const auto& l : unitL)
    for (int k = 0; k < 3; ++k) mean[k] += l[k];
  double meanNorm = std::sqrt(mean[0] * mean[0] + mean[1] * mean[1] + mean[2] * mean[2]);
  int first = 0;
  if (meanNorm > 1e-12) {
    for (auto& m : mean) m /= meanNorm;
    double best = angleBetween(unitL[0], mean);
    for (int i = 1; i < n; ++i) {
      double a = angleBetween(unitL[i], mean);
      if (a < best - kTie) best = a, first = i;
    }
  }

  // Farthest point sampling: each next light is the one whose nearest chosen light is farthest.
  std::vector<double> nearest(n, 0);
  std::vector<char> chosen(n, 0);
  std::vector<int> out{first};
  chosen[first] = 1;
  for (int i = 0; i < n; ++i) nearest[i] = angleBetween(unitL[i], unitL[first]);
  while (static_cast<int>(out.size()) < count) {
    int pick = -1;
    for (int i = 0; i < n; ++i) {
      if (chosen[i]) continue;
      if (pick < 0 || nearest[i] > nearest[pick] + kTie) pick = i;
    }
    chosen[pick] = 1;
    out.push_back(pick);
    for (int i = 0; i < n; ++i) nearest[i] = std::min(nearest[i], angleBetween(unitL[i], unitL[pick]));
  }
  std::sort(out.begin(), out.end());
  return out;
}

Image nearestPhotographBlend(const ImageStack& stack, const std::vector<std::array<double, 3>>& lights,
                             const std::array<double, 3>& light, int count) {
  const int n = stack.size();
  if (static_cast<int>(lights.size()) != n || n == 0)
    throw Error(ErrorKind::Input, "lights", kStep,
                std::to_string(lights.size()) + " light directions for " + std::to_string(n) +
                    " photographs; give one light per photograph");
  if (count <= 0)
    throw Error(ErrorKind::Usage, "--nearest", kStep, "blend at least one photograph");
  count = std::min(count, n);
  auto target = unit(light, ErrorKind::Usage, "--light");
  auto unitL = unitLights(lights, ErrorKind::Input, "lights");

  std::vector<double> angle(n);
  for (int i = 0; i < n; ++i) angle[i] = angleBetween(unitL[i], target);
  std::vector<int> order(n);
  std::iota(order.begin(), order.end(), 0);
  std::stable_sort(order.begin(), order.end(), [&](int a, int b) { return angle[a] < angle[b]; });
  order.resize(count);
  std::vector<double> weight(count);
  double total = 0;
  for (int j = 0; j < count; ++j) total += weight[j] = 1.0 / (angle[order[j]] + 1e-6);
  for (auto& w : weight) w /= total;

  // Blended in 8-bit units and rounded, as a viewer's 8-bit output; a grey stack is drawn grey
  // in all three channels. Read in bands so that a full-size capture costs a band per image.
  const int width = stack.width(), height = stack.height(), channels = stack.channels();
  Image out(width, height, 3);
  out.bitsPerSample = 8;
  out.transfer = stack.transfer();
  const int band = std::max(1, std::min(height, (1 << 20) / std::max(1, width * channels)));
  std::vector<std::uint16_t> rows(static_cast<std::size_t>(band) * width * channels);
  std::vector<double> sum(rows.size());
  for (int y0 = 0; y0 < height; y0 += band) {
    const int y1 = std::min(height, y0 + band);
    const std::size_t samples = static_cast<std::size_t>(y1 - y0) * width * channels;
    std::fill(sum.begin(), sum.begin() + samples, 0.0);
    for (int j = 0; j < count; ++j) {
      stack.readRows(order[j], y0, y1, rows.data());
      for (std::size_t i = 0; i < samples; ++i) sum[i] += weight[j] * (rows[i] / 257.0);
    }
    std::uint16_t* dst = out.pixels.data() + static_cast<std::size_t>(y0) * width * 3;
    for (std::size_t p = 0; p < samples / channels; ++p)
      for (int k = 0; k < 3; ++k) {
        double v = sum[p * channels + (channels == 3 ? k : 0)];
        dst[p * 3 + k] = static_cast<std::uint16_t>(257 * std::lround(std::clamp(v, 0.0, 255.0)));
      }
  }
  return out;
}

}  // namespace surrogate::fit
