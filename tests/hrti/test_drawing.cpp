// The sphere overlay and highlight overview refuse a circle they cannot draw with an Error
// naming the problem, never an OpenCV assertion (the stages refuse such circles first).
#include <catch2/catch.hpp>

#include <algorithm>
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

namespace {
// Columns of the picture's right edge that hold green label pixels below row `fromRow`.
bool greenOnRightEdge(const Image& picture, int fromRow) {
  for (int y = fromRow; y < picture.height; ++y) {
    const int x = picture.width - 1;
    if (picture.at(x, y, 1) > 150 * 257 && picture.at(x, y, 0) < 100 * 257) return true;
  }
  return false;
}
}  // namespace

TEST_CASE("the overlay's label of a sphere at the frame edge stays inside the picture") {
  // Black, so that any green pixel is the drawing's. The sphere touches the right edge; its
  // label, below the circle, would run past it if placed at the circle's left side.
  Image median(400, 300, 1);
  const Image overlay = drawSphereOverlay(median, {{380, 40, 30, 0.9}});
  REQUIRE(overlay.width == 400);
  CHECK_FALSE(greenOnRightEdge(overlay, 40 + 30 + 3));
  bool anyLabel = false;  // the label is drawn somewhere below the circle
  for (int y = 40 + 30 + 3; y < overlay.height && !anyLabel; ++y)
    for (int x = 0; x < overlay.width && !anyLabel; ++x) anyLabel = overlay.at(x, y, 1) > 150 * 257;
  CHECK(anyLabel);
}

TEST_CASE("highlight overview labels are the given names, inside the picture") {
  Image median(400, 300, 1);
  Highlight nearEdge;
  nearEdge.x = 199;  // at the sphere's right rim: the label would run past the crop
  nearEdge.y = 150;
  nearEdge.flag = HighlightFlag::Ok;
  const DetectedSphere sphere{150, 150, 50, 1};
  const Image numbered = drawHighlightOverview(median, sphere, {nearEdge});
  const Image named = drawHighlightOverview(median, sphere, {nearEdge}, {"IMG_0004"});
  REQUIRE(named.width == numbered.width);
  CHECK(named.pixels != numbered.pixels);  // the name, not "1"
  // Nothing red (the label's colour) in the last column.
  for (int y = 0; y < named.height; ++y) {
    INFO("row " << y);
    const int x = named.width - 1;
    CHECK_FALSE((named.at(x, y, 0) > 150 * 257 && named.at(x, y, 1) < 100 * 257));
  }
}

TEST_CASE("the highlight overview from a crop of the median is the one from the whole median") {
  // The stage reads only the sphere's surroundings (StackMedian::window); the picture must not
  // depend on it.
  Image median(400, 300, 1);
  for (int y = 0; y < median.height; ++y)
    for (int x = 0; x < median.width; ++x) median.at(x, y) = static_cast<std::uint16_t>((x * 131 + y * 977) % 65536);
  Highlight h;
  h.x = 372;
  h.y = 20;
  for (const DetectedSphere& s : {DetectedSphere{380.3, 40.7, 30.2, 0.9}, DetectedSphere{120.5, 150.25, 61, 1}}) {
    const MedianCrop crop = [&](const Rect& r) {
      REQUIRE(r.x >= 0);
      REQUIRE(r.x + r.w <= median.width);
      Image out(r.w, r.h, 1);
      for (int y = 0; y < r.h; ++y)
        for (int x = 0; x < r.w; ++x) out.at(x, y) = median.at(r.x + x, r.y + y);
      return out;
    };
    CHECK(drawHighlightOverview(median.width, median.height, crop, s, {h}, {"IMG_1"}).pixels ==
          drawHighlightOverview(median, s, {h}, {"IMG_1"}).pixels);
  }
}

TEST_CASE("the overlay on a reduced median draws the circle reduced with it") {
  // A black frame reduced 4 times: the circle of radius 40 around (201.5, 101.5) is drawn
  // around the reduced pixel (50, 25) with radius 10.
  const Image reduced(100, 75, 1);
  const Image overlay = drawSphereOverlay(reduced, {{201.5, 101.5, 40, 1}}, 4);
  REQUIRE(overlay.width == 100);
  CHECK(overlay.at(60, 25, 1) > 150 * 257);  // on the circle, right of the centre
  CHECK(overlay.at(40, 25, 1) > 150 * 257);
  CHECK(overlay.at(70, 25, 1) < 50 * 257);   // outside it
}

TEST_CASE("the overlay labels a sphere given by hand by hand, not with a confidence") {
  // The same circle detected with confidence 1 and given by hand: the labels differ, and the
  // one given by hand is the label OpenCV draws for "sphere 1  r=30.0  by hand" (its width).
  Image median(400, 300, 1);
  DetectedSphere detected{150, 100, 30, 1, 1};
  DetectedSphere given = detected;
  given.byHand = true;
  const Image a = drawSphereOverlay(median, {detected}), b = drawSphereOverlay(median, {given});
  REQUIRE(a.width == b.width);
  CHECK(a.pixels != b.pixels);
  // The label's extent: green pixels below the circle, leftmost to rightmost.
  const auto labelWidth = [](const Image& picture) {
    int left = picture.width, right = -1;
    for (int y = 100 + 30 + 3; y < picture.height; ++y)
      for (int x = 0; x < picture.width; ++x)
        if (picture.at(x, y, 1) > 150 * 257) left = std::min(left, x), right = std::max(right, x);
    return right - left;
  };
  // "by hand" (7 characters) is shorter than "conf 1.00" (9): the label is narrower.
  CHECK(labelWidth(b) < labelWidth(a));
  CHECK(labelWidth(b) > 0);
}
