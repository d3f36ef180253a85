// Whether a value given by hand fits the frame it applies to: a circle given by hand
// (--sphere), a highlight given by hand (--highlight), a region (--sphere-roi, --crop,
// --wb-region). One rule for every place that checks: the command line checks what needs no
// frame (cli/option_checks.h), the run checks the request against the capture's frame
// (run/request_checks.h), and the stages check again (defence in depth: a recorded carrier
// replayed by the verifier never went through the command line), so that a bad value is an
// error naming it, never an OpenCV assertion.
//
//   if (const std::string why = stages::sphereCircleProblem(cx, cy, r, w, h); !why.empty()) ...
#pragma once

#include <optional>
#include <string>

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
// The rule for the frame: the centre is a pixel of the frame, and the radius is at most half
// the frame's smaller side or at least half of the disc (kMinDiscShareInFrame) is inside the
// frame. The circle may reach past the frame's edge: a sphere cut by the edge happens in real
// captures (a light probe filling the frame, cropped), its visible part still shows the
// highlights, the sphere detection stage fits the circle to its visible rim, and every stage
// clips to the frame. A centre outside the frame leaves at most a sliver of the sphere, and a
// sphere much larger than the frame cannot be in the picture at all (a 400 px radius in a
// 400x300 frame, a quarter of its disc inside, gives lights at 82-88 degrees for any
// highlight): both are typos.
std::string sphereCircleProblem(double cx, double cy, double r, int width = 0, int height = 0);
inline constexpr double kMinDiscShareInFrame = 0.5;
// The share (0..1) of the disc of radius r at (cx, cy) that lies inside a width x height frame
// (pixel centres at whole numbers: the frame covers -0.5 to width - 0.5).
double discShareInFrame(double cx, double cy, double r, int width, int height);

// Why (x, y) cannot be a highlight given by hand, or "" when it can: finite coordinates >= 0;
// with a frame, inside it; with a sphere's circle, on the sphere (up to half a pixel past its
// outline, which the light direction clamps onto the outline).
std::string highlightPointProblem(double x, double y, int width = 0, int height = 0,
                                  const std::optional<SphereCircle>& sphere = std::nullopt);

// Why the rectangle x, y, w, h cannot be a region of a width x height frame, or "" when it
// can: whole numbers, x and y >= 0, w and h > 0; with a frame, wholly inside it.
std::string frameRegionProblem(double x, double y, double w, double h, int width = 0, int height = 0);

}  // namespace surrogate::stages
