// Private to src/fit: how a viewer spreads a light over a learned model's nodes (fit/learned.h).
//
//   rbf:      every captured light is a node; weight exp(-eps d^2) normalised, d the distance
//             between the unit light vectors, eps = 8 / m with m the distances' mean weighted by
//             exp(-2 d) (OpenLIME's adaptive RBF, alpha 8, beta 2, all nodes);
//   bilinear: the octahedral map of the hemisphere, rotated 45 degrees to fill the square:
//             u = (lx + ly) / s, v = (ly - lx) / s, s = |lx| + |ly| + |lz|, then (u, v) in [-1, 1]
//             -> (R - 1) (u + 1) / 2; the four nodes around it, bilinear weights (the cell clamped
//             to the grid). Node (x, y) is x + y R; its direction is the inverse map.
//
//   std::vector<NodeWeight> w = bilinearNodeWeights(12, {0.3, 0.2, 0.93});   // four nodes
#pragma once

#include <array>
#include <vector>

namespace surrogate::fit {

struct NodeWeight {
  int node = 0;
  double weight = 0;
};

// `light` unit length.
std::vector<NodeWeight> rbfNodeWeights(const std::vector<std::array<double, 3>>& nodes, const std::array<double, 3>& light);
std::vector<NodeWeight> bilinearNodeWeights(int resolution, const std::array<double, 3>& light);

// The unit direction of grid node (x, y), z >= 0.
std::array<double, 3> bilinearNodeDirection(int resolution, int x, int y);

}  // namespace surrogate::fit
