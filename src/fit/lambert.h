// Private to src/fit: least-squares Lambertian fit over a fixed set of light directions.
//
//     I(l) ~= b . l,   b = rho n   (rho: albedo, n: unit normal)
//     b = Q I,  Q = (D^T D)^-1 D^T  (3 x K, D: K x 3 directions), computed once
//
// The K = 61 directions: elevations 15, 30, 45, 60, 75 degrees x 12 azimuths (0, 30, ...
// 330 degrees), plus the zenith. Used where a model has no usable analytic maximum (PTM
// fallback) and for every HSH texel, always with the model's own values at these directions,
// so normals and albedo depend only on the file, not on the capture.
//
// The model's values at the directions are linear in its coefficients a (values = B a, B the
// K x terms table of the basis at the directions), so b = (Q B) a: texel code multiplies by
// the 3 x terms product, made once, instead of evaluating the model K times per texel.
#pragma once

#include <array>
#include <vector>

namespace surrogate::fit {

struct LambertDirections {
  std::vector<std::array<double, 3>> directions;  // K unit vectors
  std::vector<double> q;                          // 3 x K, row-major
};

const LambertDirections& lambertDirections();

// Q B for a basis table B (K x terms, row-major; K the number of directions): 3 x terms,
// row-major.
std::vector<double> lambertOfBasis(const std::vector<double>& basisTable, int terms);

// n = b / |b| when |b| > 1e-9 and b_z > 0 (a surface facing the camera); otherwise
// n = (0, 0, 1) and false.
bool normalFromLambert(const std::array<double, 3>& b, std::array<double, 3>* n);

}  // namespace surrogate::fit
