// Lights at known positions for the PTM/HSH fits (FitOptions::nearLights; fit.h describes the
// method, docs/hrti-math.md "Near lights in the fit" the formulas and the figures).
//
// Coordinates are the STACK's pixel units with the origin at pixel (0, 0)'s centre: pixel (x, y)
// of the stack is the surface point p = (x, -y, 0); X right, Y up, Z towards the camera. (The
// stage converts from the frame coordinates of the capture, crops and resizes included.)
//
// For a near light i and a pixel p:
//     direction  l_i(p) = normalize(X_i - p)
//     fall-off   f_i(p) = (|X_i - p| / referenceDistance_i)^2
// and the pixel's sample under light i is multiplied by f_i(p) before fitting, so the model is
// that of the surface lit from l_i(p) at the irradiance it would have at referenceDistance_i (the
// stage gives |X_i| measured from the frame's centre, so the frame's centre keeps its values).
// A light with near = false keeps its direction from the fit's `lights` vector and f = 1.
//
//   FitOptions options;
//   options.nearLights.assign(lights.size(), NearLight{});          // one per light
//   options.nearLights[0] = {true, {600.0, 900.0, 1500.0}, 1800.0};  // light 0 at a position
#pragma once

#include <array>

namespace surrogate::fit {

struct NearLight {
  bool near = false;                   // false: at infinity, the direction of the `lights` vector
  std::array<double, 3> position{};    // stack pixel units, see above; z > 0 (above the surface)
  double referenceDistance = 0;        // > 0, in the same units: the distance at which f = 1
};

}  // namespace surrogate::fit
