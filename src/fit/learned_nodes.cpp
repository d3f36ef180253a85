#include "fit/learned_nodes.h"

#include <algorithm>
#include <cmath>

namespace surrogate::fit {

std::vector<NodeWeight> rbfNodeWeights(const std::vector<std::array<double, 3>>& nodes, const std::array<double, 3>& light) {
  std::vector<double> distance(nodes.size());
  double num = 0, den = 0;
  for (std::size_t i = 0; i < nodes.size(); ++i) {
    const double dx = nodes[i][0] - light[0], dy = nodes[i][1] - light[1], dz = nodes[i][2] - light[2];
    distance[i] = std::sqrt(dx * dx + dy * dy + dz * dz);
    const double w = std::exp(-2.0 * distance[i]);
    num += distance[i] * w;
    den += w;
  }
  // The viewer's width follows the local spacing: the weighted mean distance is about the
  // nearest nodes' distance, so a sparse region gets a wide kernel and a dense one a narrow one.
  const double epsilon = 8.0 / (num / den);
  std::vector<NodeWeight> weights(nodes.size());
  double total = 0;
  for (std::size_t i = 0; i < nodes.size(); ++i) {
    weights[i] = {static_cast<int>(i), std::exp(-epsilon * distance[i] * distance[i])};
    total += weights[i].weight;
  }
  for (NodeWeight& w : weights) w.weight /= total;
  return weights;
}

std::vector<NodeWeight> bilinearNodeWeights(int resolution, const std::array<double, 3>& light) {
  const double s = std::abs(light[0]) + std::abs(light[1]) + std::abs(light[2]);
  const double u = ((light[0] + light[1]) / s + 1.0) / 2.0 * (resolution - 1.0);
  const double v = ((light[1] - light[0]) / s + 1.0) / 2.0 * (resolution - 1.0);
  const int sx = std::min(resolution - 2, std::max(0, static_cast<int>(std::floor(u))));
  const int sy = std::min(resolution - 2, std::max(0, static_cast<int>(std::floor(v))));
  const double dx = u - sx, dy = v - sy;
  return {{sx + sy * resolution, (1 - dx) * (1 - dy)},
          {sx + 1 + sy * resolution, dx * (1 - dy)},
          {sx + (sy + 1) * resolution, (1 - dx) * dy},
          {sx + 1 + (sy + 1) * resolution, dx * dy}};
}

std::array<double, 3> bilinearNodeDirection(int resolution, int x, int y) {
  const double u = 2.0 * x / (resolution - 1) - 1.0;
  const double v = 2.0 * y / (resolution - 1) - 1.0;
  const double ox = (u - v) / 2.0, oy = (u + v) / 2.0;
  const double oz = std::max(0.0, 1.0 - std::abs(ox) - std::abs(oy));
  const double n = std::sqrt(ox * ox + oy * oy + oz * oz);
  return {ox / n, oy / n, oz / n};
}

}  // namespace surrogate::fit
