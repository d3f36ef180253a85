// The values of a run checked against the frame they apply to, before any processing: a circle
// given by hand (--sphere), a sphere search region (--sphere-roi), a highlight given by hand
// (--highlight), a crop rectangle or grey region (--crop, --wb-region). The command line checks
// what needs no frame (cli/option_checks.h) with the same rules; the stages check again
// (defence in depth: a recorded carrier replayed by the verifier never went through the
// command line), so that a bad value is an error naming it, never an OpenCV assertion.
//
//   stages::checkRequestAgainstFrame(request, 400, 300);  // Error(Usage) naming the option
//   if (const std::string why = stages::sphereCircleProblem(cx, cy, r, w, h); !why.empty()) ...
#pragma once

#include <optional>
#include <string>

#include "stages/plan.h"

namespace surrogate::stages {

// The smallest radius of a sphere given by hand: highlight detection leaves out a rim of
// 2 pixels at the sphere's edge, so a smaller circle leaves no pixel to find a highlight in.
inline constexpr double kMinSphereRadius = 3;

// A sphere's circle in the frame's pixels (origin at the centre of the top-left pixel, y down).
struct SphereCircle {
  double cx = 0, cy = 0, r = 0;
};

// Why the circle (cx, cy, r) given by hand cannot be a sphere of a width x height frame, or ""
// when it can. With width or height 0, only what needs no frame: finite numbers, a centre at
// coordinates >= 0, a radius of at least kMinSphereRadius.
//
// The rule for the frame: the centre is a pixel of the frame and the radius at most half the
// frame's smaller side. The circle may reach past the frame's edge: a sphere cut by the edge
// happens in real captures, its visible part still shows the highlights, and every stage
// clips to the frame. A centre outside the frame leaves at most a sliver of the sphere, and
// a sphere wider than the frame's smaller side cannot be in the picture at all (a 400 px
// radius in a 400x300 frame gives lights at 82-88 degrees for any highlight): both are typos.
std::string sphereCircleProblem(double cx, double cy, double r, int width = 0, int height = 0);

// Why (x, y) cannot be a highlight given by hand, or "" when it can: finite coordinates >= 0;
// with a frame, inside it; with a sphere's circle, on the sphere (up to half a pixel past its
// outline, which the light direction clamps onto the outline).
std::string highlightPointProblem(double x, double y, int width = 0, int height = 0,
                                  const std::optional<SphereCircle>& sphere = std::nullopt);

// Why the rectangle x, y, w, h cannot be a region of a width x height frame, or "" when it
// can: whole numbers, x and y >= 0, w and h > 0; with a frame, wholly inside it.
std::string frameRegionProblem(double x, double y, double w, double h, int width = 0, int height = 0);

// Checks the request's values against a width x height frame (the capture's images), before
// any processing: the circles and highlights given by hand, the sphere search regions, a
// user crop rectangle, a white-balance grey region and the size a resize gives (at least
// kMinResizeSide pixels per side, stages/preprocess.h). A highlight given for a sphere whose
// circle is given by hand must lie on that circle, and name one of those spheres. Throws
// Error(Usage) naming the option and its value ("--sphere 900,57,45"), saying what is wrong
// and what the frame allows.
void checkRequestAgainstFrame(const RunRequest& request, int width, int height);

}  // namespace surrogate::stages
