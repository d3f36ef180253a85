// The synthetic scene: relief height field, albedo, and per-pixel radiance under a light.
#pragma once

#include <array>
#include <vector>

#include "generator/capture_generator.h"

namespace surrogate::generator {

class Scene {
 public:
  Scene(const GeneratorOptions& options, const CaptureTruth& truth);
  // Linear radiance (0..~1, highlights above 1) of pixel (x, y) under light L.
  std::array<double, 3> radiance(int x, int y, const std::array<double, 3>& light) const;

 private:
  double height(int x, int y) const { return height_[std::size_t(y) * w_ + x]; }
  bool shadowedByRelief(int x, int y, const std::array<double, 3>& l) const;
  bool shadowedBySphere(double x, double y, double z, const std::array<double, 3>& l) const;
  // Sphere contribution at sub-pixel (sx, sy); false if the point is not on a sphere.
  bool sphereRadiance(double sx, double sy, const std::array<double, 3>& l, double* out) const;

  const GeneratorOptions& o_;
  const CaptureTruth& t_;
  int w_, h_;
  std::vector<float> height_;             // pixels
  std::vector<std::array<float, 3>> normal_;
  std::vector<std::array<float, 3>> albedo_;
  double maxHeight_ = 0;
};

// renderShot() with a scene built once for all shots of a capture.
Image renderShot(const Scene& scene, const GeneratorOptions& options, const CaptureTruth& truth, int index);

}  // namespace surrogate::generator
