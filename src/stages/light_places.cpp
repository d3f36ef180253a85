#include "stages/light_places.h"

#include "carrier/advice.h"

#include <algorithm>
#include <cmath>

#include "core/error.h"
#include "core/parallel.h"
#include "core/text.h"
#include "hrti/light_position.h"

namespace surrogate::stages {

namespace {

double median(std::vector<double> v) {
  if (v.empty()) return 0;
  std::sort(v.begin(), v.end());
  const std::size_t m = v.size() / 2;
  return v.size() % 2 ? v[m] : (v[m - 1] + v[m]) / 2;
}

// The stated distance in frame widths; 0 when none is stated (auto or infinity).
double statedWidths(const StatedDistance& d, const LightDirectionsOptions& options,
                    const std::vector<MeasuredLight>& measured, int width) {
  if (d.kind == StatedDistance::Kind::FrameWidths) return d.value;
  if (d.kind != StatedDistance::Kind::Millimetres) return 0;
  if (options.sphereDiameterMm <= 0)
    throw Error(ErrorKind::Usage, "--light-distance " + options.lightDistance, "light directions",
                "is a length, and the frame's scale comes from the spheres' real size: add --sphere-diameter MM, "
                "or give the distance in frame widths (e.g. --light-distance 3)");
  // The spheres' radius in pixels (their mean over the images that use them) gives millimetres
  // per pixel: diameter / (2 r).
  double sum = 0;
  int count = 0;
  for (const MeasuredLight& m : measured)
    for (const hrti::SphereEvidence& e : m.evidence) {
      sum += e.sphere.r;
      ++count;
    }
  if (count == 0 || sum <= 0) return 0;
  const double widthMm = width * options.sphereDiameterMm / (2 * sum / count);
  return d.value / widthMm;
}

}  // namespace

PlacedLights placeLights(const LightDirectionsOptions& options, const std::vector<MeasuredLight>& measured,
                         const InputImages& inputs, int width, int height, carrier::Carrier& carrier,
                         const std::string& stepId, carrier::Result& result, int threads) {
  const StatedDistance stated = StatedDistance::parse(options.lightDistance, "lightDistance");
  const double widths = statedWidths(stated, options, measured, width);
  if (widths > 0 && widths < kMinLightDistanceWidths)
    throw Error(ErrorKind::Usage, "--light-distance " + options.lightDistance, "light directions",
                "is " + fixedDecimals(widths, 2) + " frame widths from the frame's centre: the light would stand over "
                "the object; check the distance and --sphere-diameter");
  if (stated.kind == StatedDistance::Kind::Millimetres)
    result.add("value").set("name", "lightDistanceWidths").set("value", formatNumber(widths)).set("unit", "frame widths");

  PlacedLights out;
  out.places.frameWidth = width;
  out.places.frameHeight = height;
  std::vector<std::string> bySpheres, byDistance, untrusted;
  std::string firstReason;
  std::vector<double> bounds;
  // The spheres first: triangulation is orthographic (hrti/light_position.h); with the
  // perspective model only a stated distance places the lights.
  std::vector<hrti::NearLightPosition> triangulated(measured.size());
  std::vector<double> placedWidths;
  // Each light on its own (its bound's gaussianRadius is most of the time), written at its index.
  parallelFor(measured.size(), 1, threads, [&](std::size_t begin, std::size_t end) {
    for (std::size_t n = begin; n < end; ++n) {
      const MeasuredLight& m = measured[n];
      if (stated.kind == StatedDistance::Kind::Infinity || options.model != "orthographic" || m.evidence.size() < 2)
        continue;
      triangulated[n] = hrti::positionFromSpheres(m.evidence, width, height, m.sphereNumbers);
    }
  });
  for (const hrti::NearLightPosition& p : triangulated)
    if (p.trusted) placedWidths.push_back(p.distancePx / width);
  // Stated and measured both: the spheres' positions are used; a statement far from them is
  // worth a word (the wrong unit, or the dome's diameter given for its radius).
  if (widths > 0 && placedWidths.size() >= 3 && std::abs(median(placedWidths) / widths - 1) > 0.2)
    carrier::addWarning(carrier, stepId,
                        {"the two spheres place the lights at another distance than the one stated "
                         "(--light-distance); the lights they place take their positions, the others the stated "
                         "distance",
                         carrier::Usable::WithCare,
                         "if the stated distance is wrong, the lights it places are wrong too",
                         "check the distance you stated: it is measured from the frame's centre in frame widths (a "
                         "dome's radius, not its diameter)",
                         std::to_string(placedWidths.size()) + " lights placed at a median " +
                             fixedDecimals(median(placedWidths), 2) + " frame widths; stated " + fixedDecimals(widths, 2)});
  // No distance stated, and the spheres placed enough lights (at least 3, and a quarter of
  // them) to say how far the flash was held: the others go at the median of their distances,
  // which stands for the distance a photographer would have stated.
  double fallback = widths;
  std::string fallbackSource = "stated-distance";
  if (fallback == 0 && stated.kind == StatedDistance::Kind::Auto && placedWidths.size() >= 3 &&
      4 * placedWidths.size() >= measured.size()) {
    fallback = median(placedWidths);
    fallbackSource = "spheres-median";
  }
  for (std::size_t n = 0; n < measured.size(); ++n) {
    const MeasuredLight& m = measured[n];
    LightPlace place;
    double bound = -1;
    std::string source;
    double distanceBound = -1;
    if (triangulated[n].trusted) {
      const hrti::NearLightPosition& p = triangulated[n];
      place = {true, p.position};
      bound = p.directionBoundDeg;
      distanceBound = p.distanceBoundPx / width;
      source = "spheres";
      bySpheres.push_back(inputs[n].stem);
      bounds.push_back(distanceBound);
    } else if (!triangulated[n].reason.empty()) {
      untrusted.push_back(inputs[n].stem);
      if (firstReason.empty()) firstReason = inputs[n].stem + ": " + triangulated[n].reason;
    }
    if (!place.near && fallback > 0) {
      // Along each sphere's own reflected ray to that distance; the spheres' points averaged
      // (they differ by the error of the highlights).
      std::array<double, 3> sum{0, 0, 0};
      bool ok = true;
      for (std::size_t k = 0; k < m.evidence.size(); ++k) {
        const hrti::PositionAtDistance p =
            hrti::positionAtDistance(m.evidence[k].sphere, m.perSphere[k], fallback * width, width, height);
        if (!p.ok && fallbackSource == "stated-distance")
          throw Error(ErrorKind::Usage, "--light-distance " + options.lightDistance, "light directions",
                      inputs[n].relativePath + ", sphere " + std::to_string(m.sphereNumbers[k]) + ": " + p.reason);
        ok = ok && p.ok;
        for (int c = 0; c < 3; ++c) sum[c] += p.position[c] / m.evidence.size();
      }
      if (!m.evidence.empty() && ok) {
        place = {true, sum};
        source = fallbackSource;
        byDistance.push_back(inputs[n].stem);
      }
    }
    out.places.lights.push_back(place);
    out.uncertaintyDeg.push_back(bound);
    out.perSphereFromCentre.emplace_back();
    for (std::size_t k = 0; place.near && k < m.evidence.size(); ++k) {
      hrti::Vec3 point, ray;
      hrti::mirrorRay(m.evidence[k].sphere, m.evidence[k].highlight.x, m.evidence[k].highlight.y, width, height,
                      point, ray);
      double t = 0;
      for (int c = 0; c < 3; ++c) t += (place.position[c] - point[c]) * ray[c];
      t = std::max(t, 0.0);
      const hrti::Vec3 nearest = {point[0] + t * ray[0], point[1] + t * ray[1], point[2] + t * ray[2]};
      const hrti::Vec3 d = hrti::directionOfPosition(nearest);
      out.perSphereFromCentre.back().push_back({d[0], d[1], d[2]});
    }
    if (!place.near) {
      out.directions.push_back(m.direction);
      continue;
    }
    const hrti::Vec3 d = hrti::directionOfPosition(place.position);
    out.directions.push_back({d[0], d[1], d[2]});
    const double distance = std::hypot(place.position[0], place.position[1], place.position[2]) / width;
    auto& item = result.add("nearLight").set("image", inputs[n].fileId).set("x", place.position[0])
                     .set("y", place.position[1]).set("z", place.position[2]).set("distance", distance)
                     .set("source", source);
    if (distanceBound >= 0) item.set("distanceBound", distanceBound);
  }

  std::vector<std::string> parts;
  if (!bySpheres.empty())
    parts.push_back(std::to_string(bySpheres.size()) + " placed by the two spheres (median distance " +
                    fixedDecimals(median(placedWidths), 2) +
                    " frame widths, 95 % bound " + fixedDecimals(median(bounds), 2) + ")");
  if (!byDistance.empty())
    parts.push_back(std::to_string(byDistance.size()) +
                    (fallbackSource == "spheres-median" ? " at the median distance of those, " : " at the stated distance, ") +
                    fixedDecimals(fallback, 2) + " frame widths");
  const std::size_t far = measured.size() - bySpheres.size() - byDistance.size();
  const bool someNear = !bySpheres.empty() || !byDistance.empty();
  if (far > 0 && someNear) parts.push_back(std::to_string(far) + " at infinity (a direction only)");
  if (someNear)
    carrier.addLog("info", stepId, "light positions: " + listedInFull(parts, "; ") +
                                       "; the fit gives each pixel its own light direction and brings its "
                                       "values to the frame centre's light (inverse square)");
  if (!untrusted.empty() && !someNear) {
    // No light placed: the capture's lights are far (the rays parallel within their
    // uncertainty), as most captures' are.
    carrier.addLog("info", stepId,
                   "the two spheres see the lights as at infinity (" + std::to_string(untrusted.size()) + " of " +
                       std::to_string(measured.size()) + " images checked; e.g. " + firstReason +
                       "); if the light was nearer, state its distance with --light-distance D (frame widths)");
  } else if (!untrusted.empty()) {
    const std::string couldNot = "the two spheres could not place the light of " + std::to_string(untrusted.size()) +
                                 " of the " + std::to_string(measured.size()) + " images (" + listedInFull(untrusted) +
                                 "), e.g. " + firstReason;
    if (!byDistance.empty())
      carrier.addLog("info", stepId,
                     couldNot + (fallbackSource == "spheres-median"
                                     ? "; they are placed at the median distance of the lights the spheres "
                                       "placed (state the distance with --light-distance D if it was another)"
                                     : "; they are placed at the stated distance"));
    else
      carrier::addWarning(carrier, stepId,
                          {"the two spheres could not place the light of " + std::to_string(untrusted.size()) +
                               " of the " + std::to_string(measured.size()) +
                               " images, so those lights are taken as far away (parallel rays)",
                           carrier::Usable::WithCare,
                           "if the flash was held near, the shading of those photographs is modelled less well",
                           "state how far the flash was with --light-distance D (in frame widths) to place them",
                           listedInFull(untrusted) + "; e.g. " + firstReason});
  }
  return out;
}

}  // namespace surrogate::stages
