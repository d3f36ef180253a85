// Private to src/stages: where each light was (docs/hrti-math.md, "Near lights"), for
// LightDirections. Two spheres place a light by triangulation where its uncertainty allows
// (hrti/light_position.h); otherwise a stated distance (--light-distance) places it along the
// ray its highlight reflects; otherwise it stays at infinity, a direction. Each placed light's
// direction becomes the one from the frame's centre (X / |X|), which is what .lp files and the
// fit take as "the" light's direction.
#pragma once

#include <array>
#include <string>
#include <vector>

#include "carrier/carrier.h"
#include "hrti/light_uncertainty.h"
#include "stages/inputs.h"
#include "stages/light_directions_stage.h"

namespace surrogate::stages {

// One image's light as measured: its direction (the spheres' mean), each usable sphere's own
// direction and evidence, with the sphere's index in the capture.
struct MeasuredLight {
  std::array<double, 3> direction{};
  std::vector<hrti::SphereEvidence> evidence;
  std::vector<std::array<double, 3>> perSphere;  // direction seen from each sphere of `evidence`
  std::vector<int> sphereNumbers;
};

struct PlacedLights {
  LightPlaces places;
  std::vector<std::array<double, 3>> directions;  // X / |X| for a placed light, else as measured
  std::vector<double> uncertaintyDeg;             // < 0: keep the measured one
  // For a placed light, each sphere's own estimate seen from the frame's centre (the point of its
  // ray nearest the position), in the order of MeasuredLight::evidence: what spheres-disagree
  // compares, since the directions seen from two spheres differ by the parallax of a near light.
  std::vector<std::vector<std::array<double, 3>>> perSphereFromCentre;
};

// Places every image's light and records it: a `nearLight` item per placed light, the stated
// distance in frame widths (value lightDistanceWidths), and one log line saying how many lights
// each way placed and why the others were not. Error(Usage) for a stated length without
// --sphere-diameter, or a stated distance no light can have (closer than a sphere). The lights
// are triangulated on `threads` threads (the same results at any count).
PlacedLights placeLights(const LightDirectionsOptions& options, const std::vector<MeasuredLight>& measured,
                         const InputImages& inputs, int width, int height, carrier::Carrier& carrier,
                         const std::string& stepId, carrier::Result& result, int threads);

}  // namespace surrogate::stages
