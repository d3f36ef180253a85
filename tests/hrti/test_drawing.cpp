// The sphere overlay and highlight overview refuse a circle they cannot draw with an Error
// naming the problem, never an OpenCV assertion (the stages refuse such circles first).
#include <catch2/catch.hpp>

#include <cmath>

#include "core/error.h"
#include "hrti/drawing.h"

using namespace surrogate;
using namespace surrogate::hrti;

namespace {
Image grey(int w, int h) {
  Image im(w, h, 1);
  for (auto& v : im.pixels) v = 30000;
  return im;
}
}  // namespace

TEST_CASE("drawing a circle inside or cut by the frame edge works") {
  const Image median = grey(400, 300);
  CHECK(drawSphereOverlay(median, {{339, 57, 45, 1}, {395, 5, 40, 1}}).width == 400);
  CHECK(drawHighlightOverview(median, {395, 5, 40, 1}, {Highlight{}}).width > 0);
}

TEST_CASE("drawing a circle outside the frame or with no radius is an Error") {
  const Image median = grey(400, 300);
  for (const DetectedSphere& s : {DetectedSphere{900, 57, 45, 1}, DetectedSphere{339, 57, -5, 1},
                                  DetectedSphere{339, 57, 0, 1}, DetectedSphere{339, -500, 45, 1},
                                  DetectedSphere{std::nan(""), 57, 45, 1}}) {
    INFO(s.cx << "," << s.cy << "," << s.r);
    CHECK_THROWS_AS(drawSphereOverlay(median, {s}), Error);
    CHECK_THROWS_AS(drawHighlightOverview(median, s, {Highlight{}}), Error);
  }
}
