// The synthetic scene: relief height field, albedo, and per-pixel radiance under a light.
#pragma once

#include <array>
#include <vector>

#include "generator/capture_generator.h"

namespace surrogate::generator {

// The exposure of a shot: a white surface facing the light at 80 % of full scale.
inline constexpr double kExposure = 0.8;

// The light of one shot: its direction, and for a near light its position (frame coordinates,
// capture_generator.h) and the highlight each sphere shows under it.
struct ShotLight {
  std::array<double, 3> direction{};  // unit: the distant light's, or X / |X|
  bool near = false;
  std::array<double, 3> position{};   // pixels (near only)
  double distanceSquared = 0;         // |position|^2 (near only)
  std::vector<std::array<double, 2>> highlights;  // pixels (x, y down), one per sphere
};

class Scene {
 public:
  Scene(const GeneratorOptions& options, const CaptureTruth& truth);
  // The light of shot `index`.
  ShotLight shotLight(int index) const;
  // Linear radiance (0..~1, highlights above 1) of pixel (x, y) under the light; without the
  // flash (`flash` false), under the room's ambient light alone.
  std::array<double, 3> radiance(int x, int y, const ShotLight& light, bool flash = true) const;
  // The true normal at pixel (x, y): the sphere's where its centre is on a sphere, else the relief's.
  std::array<double, 3> normal(int x, int y) const;

 private:
  double height(int x, int y) const { return height_[std::size_t(y) * w_ + x]; }
  // The direction towards the light from the point at pixel (px, py) (y down, sub-pixel) and
  // height z, and the inverse-square factor (|X| / |X - p|)^2 (1 at infinity).
  void lightAt(const ShotLight& light, double px, double py, double z, std::array<double, 3>* l, double* falloff) const;
  bool shadowedByRelief(int x, int y, const std::array<double, 3>& l) const;
  bool shadowedBySphere(double x, double y, double z, const std::array<double, 3>& l) const;
  // Sphere contribution at sub-pixel (sx, sy); false if the point is not on a sphere.
  bool sphereRadiance(double sx, double sy, const ShotLight& light, bool flash, double* out) const;
  // The room (a bright window, dim walls) seen in direction r, mirrored by a sphere.
  double environment(double rx, double ry, double rz) const;
  // The lens glare streaks of the highlights at pixel (x, y).
  double glare(int x, int y, const ShotLight& light) const;

  struct Speck { double x, y, radius, brightness; };  // pixels; brightness before the light
  std::vector<Speck> specks_;
  std::array<double, 3> window_{}, windowU_{}, windowV_{};  // the window's direction and its axes
  double glareCos_ = 1, glareSin_ = 0;                      // the streaks' direction in the image

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
// trueNormals() with that scene.
Image trueNormals(const Scene& scene, const GeneratorOptions& options);

}  // namespace surrogate::generator
