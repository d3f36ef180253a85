// Light directions in the end-to-end tests: read from an .lp here, not by formats/lp (the code
// under test), and compared with a reference (a dataset's or the generator's) as the angle
// between directions, median and max over the images.
#pragma once

#include <catch2/catch.hpp>

#include <algorithm>
#include <array>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

namespace e2e {

using Direction = std::array<double, 3>;

// The directions of an .lp file, in its order: the count, then "NAME x y z" lines.
inline std::vector<Direction> lpLights(const std::filesystem::path& lp) {
  std::ifstream in(lp);
  int n = 0;
  in >> n;
  std::vector<Direction> out(n);
  std::string name;
  for (Direction& d : out) in >> name >> d[0] >> d[1] >> d[2];
  return out;
}

// The angle between two directions, in degrees (neither need be of unit length).
inline double angleDeg(const Direction& a, const Direction& b) {
  const double na = std::sqrt(a[0] * a[0] + a[1] * a[1] + a[2] * a[2]);
  const double nb = std::sqrt(b[0] * b[0] + b[1] * b[1] + b[2] * b[2]);
  const double d = (a[0] * b[0] + a[1] * b[1] + a[2] * b[2]) / (na * nb);
  return std::acos(std::clamp(d, -1.0, 1.0)) * 180 / M_PI;
}

struct LightErrors {
  double median = 0, max = 0;
};

// Image by image, in the same order: the median (the lower middle) and the largest angle.
inline LightErrors lightErrors(const std::vector<Direction>& got, const std::vector<Direction>& reference) {
  REQUIRE(got.size() == reference.size());
  std::vector<double> e;
  for (std::size_t i = 0; i < got.size(); ++i) e.push_back(angleDeg(got[i], reference[i]));
  std::sort(e.begin(), e.end());
  return {e[(e.size() - 1) / 2], e.back()};
}

}  // namespace e2e
