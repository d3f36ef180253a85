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

TEST_CASE("labels of clustered highlights never overlap each other or a mark, and stay inside the picture") {
  // Twenty highlights within 6 px of each other (lights close together), labels 70x20 px, in a
  // 600x600 overview: every label placed, no two boxes sharing a pixel, none over a mark.
  std::vector<std::pair<int, int>> marks, sizes;
  for (int k = 0; k < 20; ++k) {
    marks.emplace_back(300 + k % 4 * 2, 300 + k / 4);
    sizes.emplace_back(70, 20);
  }
  const auto places = placeLabels(marks, sizes, 600, 600, 4);
  REQUIRE(places.size() == marks.size());
  const auto disjoint = [](const Rect& a, const Rect& b) {
    return a.x + a.w <= b.x || b.x + b.w <= a.x || a.y + a.h <= b.y || b.y + b.h <= a.y;
  };
  for (std::size_t i = 0; i < places.size(); ++i) {
    INFO("label " << i);
    REQUIRE(places[i]);
    const Rect& r = *places[i];
    CHECK(r.w == 70);
    CHECK(r.h == 20);
    CHECK(r.x >= 0);
    CHECK(r.y >= 0);
    CHECK(r.x + r.w <= 600);
    CHECK(r.y + r.h <= 600);
    for (std::size_t j = 0; j < i; ++j) CHECK(disjoint(r, *places[j]));
    for (const auto& [mx, my] : marks) CHECK(disjoint(r, Rect{mx - 4, my - 4, 9, 9}));
  }
  // A lone mark's label keeps the place labels always had: right of it, its bottom at the mark.
  const auto lone = placeLabels({{300, 300}}, {{70, 20}}, 600, 600, 4);
  REQUIRE(lone[0]);
  CHECK(lone[0]->x == 300 + 4 + 3);
  CHECK(lone[0]->y == 300 - 20 + 1);
  // The same marks, the same places.
  const auto again = placeLabels(marks, sizes, 600, 600, 4);
  for (std::size_t i = 0; i < places.size(); ++i)
    CHECK((again[i] && again[i]->x == places[i]->x && again[i]->y == places[i]->y));
  // More labels than the picture holds: those left over get no place, the others still none
  // overlapping (a 100x40 picture has room for two labels of 70x20 at most, one above the
  // other, and the marks in its middle take part of that).
  std::vector<std::pair<int, int>> inside;
  for (int k = 0; k < 20; ++k) inside.emplace_back(48 + k % 4, 18 + k / 4);
  const auto crowded = placeLabels(inside, sizes, 100, 40, 4);
  int placed = 0;
  for (std::size_t i = 0; i < crowded.size(); ++i)
    if (crowded[i]) {
      ++placed;
      for (std::size_t j = 0; j < i; ++j)
        if (crowded[j]) CHECK(disjoint(*crowded[i], *crowded[j]));
    }
  CHECK(placed <= 2);
}

TEST_CASE("the overview of clustered highlights draws each label once, none over another") {
  // Black frame: the labels' pixels are the only red ones away from the marks. With 12
  // highlights at nearly one place, each label is drawn (its red pixels exist far from the
  // cluster) and the overview is the same twice.
  Image median(400, 300, 1);
  const DetectedSphere sphere{200, 150, 60, 1};
  std::vector<Highlight> cluster(12);
  std::vector<std::string> names;
  for (int k = 0; k < 12; ++k) {
    cluster[k].x = 200 + k % 3;
    cluster[k].y = 150 + k / 3;
    cluster[k].flag = HighlightFlag::Ok;
    names.push_back("IMG_00" + std::to_string(10 + k));
  }
  const Image a = drawHighlightOverview(median, sphere, cluster, names);
  CHECK(a.pixels == drawHighlightOverview(median, sphere, cluster, names).pixels);
  // Rows holding red: the twelve labels stacked need more than 12 x 13 px of rows.
  int redRows = 0;
  for (int y = 0; y < a.height; ++y) {
    bool red = false;
    for (int x = 0; x < a.width && !red; ++x) red = a.at(x, y, 0) > 150 * 257 && a.at(x, y, 1) < 100 * 257;
    redRows += red;
  }
  CHECK(redRows > 12 * 13);
}
