#include <algorithm>
#include <array>
#include <cmath>

#include "core/error.h"
#include "core/parallel.h"
#include "generator/capture_generator.h"
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
  if (o.spheres == 2) t.spheres.push_back({r + 14 + 6.1 * jitterY, r + 13 + 4.9 * jitterX, r - 0.29 * jitterY});
  return t;
}

Image renderShot(const GeneratorOptions& o, const CaptureTruth& t, int index) {
  return renderShot(Scene(o, t), o, t, index);
}

Image renderShot(const Scene& scene, const GeneratorOptions& o, const CaptureTruth& t, int index) {
  Image im(o.width, o.height, 3);
  im.transfer = Transfer::Linear;
  const auto& l = t.lights.at(index);
  const double exposure = index == o.darkFrame ? kExposure * kDarkExposure : kExposure;
  const bool flash = index != o.noFlashFrame;
  parallelFor(o.height, 16, effectiveThreads(o.threads), [&](std::size_t y0, std::size_t y1) {
    for (int y = static_cast<int>(y0); y < static_cast<int>(y1); ++y) {
      for (int x = 0; x < o.width; ++x) {
        const auto rad = scene.radiance(x, y, l, flash);
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
