#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>

#include "core/error.h"
#include "core/parallel.h"
#include "generator/capture_generator.h"
#include "generator/chart.h"
#include "generator/random.h"
#include "generator/scene.h"

namespace surrogate::generator {

CaptureTruth planCapture(const GeneratorOptions& o) {
  if (o.images < 1 || o.images > 1000 || o.width < 64 || o.height < 64 || o.spheres < 1 ||
      o.spheres > 2 || o.sphereRadius < 5 || 2 * o.sphereRadius + 20 > std::min(o.width, o.height))
    throw Error(ErrorKind::Usage, "", "generator",
                "impossible options: 1-1000 images, at least 64x64 pixels, 1 or 2 spheres that fit the frame");
  const auto shot = [&](int i) { return i == -1 || (i >= 0 && i < o.images); };
  if (!shot(o.darkFrame) || !shot(o.noFlashFrame) || (o.darkFrame >= 0 && o.darkFrame == o.noFlashFrame))
    throw Error(ErrorKind::Usage, "", "generator", "the dark frame and the frame without flash are two different shots of the capture");
  if (o.dustSpecks < 0 || o.dustSpecks > 100 || !(o.glare >= 0 && o.glare <= 2))
    throw Error(ErrorKind::Usage, "", "generator", "impossible options: 0-100 dust specks, glare 0-2 of full scale");
  if (!(o.lightConeDeg >= 0 && o.lightConeDeg < 90) ||
      (o.lightConeDeg > 0 && !(o.lightConeElevationDeg <= 90 && o.lightConeElevationDeg - o.lightConeDeg >= kMinConeElevationDeg)))
    throw Error(ErrorKind::Usage, "", "generator",
                "impossible light cone: its angle under 90 degrees, and its direction's elevation at most 90 and at "
                "least the angle plus " + std::to_string(static_cast<int>(kMinConeElevationDeg)) +
                    " degrees, so that every light stays above the horizon");
  if (!(o.lightDistance == 0 || (o.lightDistance >= kMinLightDistance && o.lightDistance <= 1e6)))
    throw Error(ErrorKind::Usage, "--light-distance", "generator",
                "is 0 (lights at infinity) or between " + std::to_string(static_cast<int>(kMinLightDistance)) +
                    " and 1000000 frame widths from the frame's centre: a nearer light would hang over the frame");
  if (!(o.sphereSeparation >= 0) || (o.sphereSeparation > 0 && o.spheres != 2))
    throw Error(ErrorKind::Usage, "--sphere-separation", "generator",
                "is the distance in pixels between the centres of two spheres: give --spheres 2 with it");
  if (!(o.exposure > 0 && o.exposure <= 100))
    throw Error(ErrorKind::Usage, "--exposure", "generator", "multiplies the exposure: give a number above 0, at most 100");
  for (double m : o.colourCast)
    if (!(std::abs(m) <= 10))
      throw Error(ErrorKind::Usage, "--colour-cast", "generator", "is a matrix of numbers within -10..10");
  CaptureTruth t;
  // Lights: elevations evenly spread in sin(elevation) between 15 and 75 degrees, azimuths on
  // a golden-angle spiral, rotated by the seed: full, irregular coverage of the hemisphere.
  const double lo = std::sin(15 * M_PI / 180), hi = std::sin(75 * M_PI / 180);
  const double rotation = 2 * M_PI * uniform(hash3(o.seed, 1, 0));
  // A narrow cone: the lights evenly over the cap within lightConeDeg of the direction at
  // lightConeElevationDeg (equal areas: 1 - cos(angle) in equal steps), azimuths on the same
  // golden-angle spiral around it.
  const double coneElevation = o.lightConeElevationDeg * M_PI / 180, cone = o.lightConeDeg * M_PI / 180;
  const std::array<double, 3> axis = {std::cos(coneElevation) * std::cos(rotation),
                                      std::cos(coneElevation) * std::sin(rotation), std::sin(coneElevation)};
  // Two unit vectors across the axis: the horizontal one, and the one up the axis' meridian.
  const std::array<double, 3> across = {-std::sin(rotation), std::cos(rotation), 0};
  const std::array<double, 3> up = {-std::sin(coneElevation) * std::cos(rotation),
                                    -std::sin(coneElevation) * std::sin(rotation), std::cos(coneElevation)};
  for (int i = 0; o.lightConeDeg > 0 && i < o.images; ++i) {
    const double c = 1 - (1 - std::cos(cone)) * (i + 0.5) / o.images, sn = std::sqrt(1 - c * c);
    const double azimuth = i * M_PI * (3 - std::sqrt(5.0));
    std::array<double, 3> l;
    for (int k = 0; k < 3; ++k)
      l[k] = c * axis[k] + sn * (std::cos(azimuth) * across[k] + std::sin(azimuth) * up[k]);
    t.lights.push_back(l);
  }
  for (int i = 0; o.lightConeDeg == 0 && i < o.images; ++i) {
    const double z = o.images == 1 ? std::sin(45 * M_PI / 180) : hi - (hi - lo) * i / (o.images - 1);
    const double azimuth = rotation + i * M_PI * (3 - std::sqrt(5.0));
    const double rxy = std::sqrt(1 - z * z);
    t.lights.push_back({rxy * std::cos(azimuth), rxy * std::sin(azimuth), z});
  }
  // Spheres near the top corners, at sub-pixel positions.
  const double r = o.sphereRadius;
  const double jitterX = uniform(hash3(o.seed, 2, 0)), jitterY = uniform(hash3(o.seed, 2, 1));
  t.spheres.push_back({o.width - r - 12 - 7.3 * jitterX, r + 12 + 5.7 * jitterY, r + 0.37 * jitterX});
  if (o.spheres == 2 && o.sphereSeparation == 0)
    t.spheres.push_back({r + 14 + 6.1 * jitterY, r + 13 + 4.9 * jitterX, r - 0.29 * jitterY});
  if (o.spheres == 2 && o.sphereSeparation > 0) {
    // On the first one's row, to its left; apart (2 px between the discs at least) and inside
    // the frame with the same 12 px margin as the first.
    const SphereTruth& first = t.spheres[0];
    const SphereTruth second = {first.cx - o.sphereSeparation, first.cy, r - 0.29 * jitterY};
    const double least = first.r + second.r + 2, most = first.cx - second.r - 12;
    if (o.sphereSeparation < least || o.sphereSeparation > most) {
      char range[96];
      std::snprintf(range, sizeof range, "between %.0f and %.0f", std::ceil(least), std::floor(most));
      throw Error(ErrorKind::Usage, "--sphere-separation", "generator",
                  std::string("puts the two spheres ") + (o.sphereSeparation < least ? "over each other" : "out of the frame") +
                      ": give " + range + " pixels for spheres of radius " + std::to_string(static_cast<int>(r)) +
                      " in a frame " + std::to_string(o.width) + " pixels wide");
    }
    t.spheres.push_back(second);
  }
  if (o.colourChart) t.chart = planChart(o, t.spheres);
  if (o.lightDistance > 0) {
    // Each light at D frame widths along its direction; it must stand above every sphere and
    // the relief (at most 0.15 of the frame's smaller side, scene.cpp), or the scene's cast
    // shadows and the sphere's lobe would see it from below.
    double top = 0.15 * std::min(o.width, o.height) + 2;
    for (const SphereTruth& s : t.spheres) top = std::max(top, 2 * s.r + 1);
    for (std::size_t i = 0; i < t.lights.size(); ++i) {
      const double d = o.lightDistance * o.width;
      t.positions.push_back({d * t.lights[i][0], d * t.lights[i][1], d * t.lights[i][2]});
      if (t.positions.back()[2] <= top) {
        char what[200];
        std::snprintf(what, sizeof what,
                      "puts light %zu (elevation %.1f degrees) %.0f pixels above the plane, not above the "
                      "spheres and the relief (%.0f pixels): give a larger distance",
                      i + 1, std::asin(t.lights[i][2]) * 180 / M_PI, t.positions.back()[2], top);
        throw Error(ErrorKind::Usage, "--light-distance", "generator", what);
      }
    }
  }
  return t;
}

Image trueNormals(const GeneratorOptions& o, const CaptureTruth& t) { return trueNormals(Scene(o, t), o); }

Image trueNormals(const Scene& scene, const GeneratorOptions& o) {
  Image im(o.width, o.height, 3);
  im.transfer = Transfer::Linear;
  parallelFor(o.height, 16, effectiveThreads(o.threads), [&](std::size_t y0, std::size_t y1) {
    for (int y = static_cast<int>(y0); y < static_cast<int>(y1); ++y)
      for (int x = 0; x < o.width; ++x) {
        const auto n = scene.normal(x, y);
        for (int c = 0; c < 3; ++c)
          im.at(x, y, c) = static_cast<std::uint16_t>(std::clamp(std::lround((n[c] + 1) / 2 * 65535), 0L, 65535L));
      }
  });
  return im;
}

Image renderShot(const GeneratorOptions& o, const CaptureTruth& t, int index) {
  return renderShot(Scene(o, t), o, t, index);
}

Image renderShot(const Scene& scene, const GeneratorOptions& o, const CaptureTruth& /*the scene's own*/, int index) {
  Image im(o.width, o.height, 3);
  im.transfer = Transfer::Linear;
  const ShotLight l = scene.shotLight(index);
  // o.exposure 1 and no cast: the bits of a capture made before they existed.
  const double exposure = (index == o.darkFrame ? kExposure * kDarkExposure : kExposure) * o.exposure;
  const bool cast = o.colourCast != kNoColourCast;
  const auto& m = o.colourCast;
  const bool flash = index != o.noFlashFrame;
  parallelFor(o.height, 16, effectiveThreads(o.threads), [&](std::size_t y0, std::size_t y1) {
    for (int y = static_cast<int>(y0); y < static_cast<int>(y1); ++y) {
      for (int x = 0; x < o.width; ++x) {
        auto rad = scene.radiance(x, y, l, flash);
        if (cast)  // the camera's response to the scene's light
          rad = {m[0] * rad[0] + m[1] * rad[1] + m[2] * rad[2], m[3] * rad[0] + m[4] * rad[1] + m[5] * rad[2],
                 m[6] * rad[0] + m[7] * rad[1] + m[8] * rad[2]};
        for (int c = 0; c < 3; ++c) {
          const double signal = rad[c] * exposure * 65535;
          const std::uint64_t h = hash3(o.seed * 1000003 + index, static_cast<std::uint64_t>(y) * o.width + x, c);
          const double sigma = std::sqrt(o.noise * o.noise + 2.0 * std::max(0.0, signal));
          const double v = signal + (o.noise > 0 ? sigma * gaussian(h) : 0);
          im.at(x, y, c) = static_cast<std::uint16_t>(std::clamp(std::lround(v), 0L, 65535L));
        }
      }
    }
  });
  return im;
}

}  // namespace surrogate::generator
