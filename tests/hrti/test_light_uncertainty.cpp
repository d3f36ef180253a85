// The light's uncertainty (hrti/light_uncertainty.h): the propagation through the light model
// against closed forms of the mirror sphere, the 95 % radius against the Gaussian's, and the
// terms' behaviour (by hand, several spheres).
#include <catch2/catch.hpp>

#include <cmath>

#include "hrti/light_uncertainty.h"

using namespace surrogate::hrti;

namespace {

// The 1-sigma angle (radians) along the tangent direction t (unit, 3D) of a covariance.
double sigmaAlong(const LightCovariance& c, const std::array<double, 3>& t) {
  std::array<double, 3> e1, e2;
  tangentBasis(c.direction, e1, e2);
  const double a = t[0] * e1[0] + t[1] * e1[1] + t[2] * e1[2], b = t[0] * e2[0] + t[1] * e2[1] + t[2] * e2[2];
  return std::sqrt(a * a * c.c[0][0] + 2 * a * b * c.c[0][1] + b * b * c.c[1][1]);
}

double trace(const LightCovariance& c) { return c.c[0][0] + c.c[1][1]; }

Highlight highlightAt(double x, double y, HighlightFlag flag = HighlightFlag::Ok) {
  Highlight h;
  h.x = x;
  h.y = y;
  h.flag = flag;
  h.confidence = 1;
  return h;
}

}  // namespace

TEST_CASE("orthographic: a highlight moved d px near the centre turns the light by 2 d / r") {
  // L = 2 (N.V) N - V: at the centre N turns by d / r and L by twice that.
  const DetectedSphere s{300, 200, 80, 1};
  const double sigma = 0.7;
  double in[5][5] = {};
  in[0][0] = in[1][1] = sigma * sigma;
  const LightCovariance c = propagate(s, 300, 200, in, nullptr);
  CHECK(std::sqrt(c.c[0][0]) == Approx(2 * sigma / 80).epsilon(1e-4));
  CHECK(std::sqrt(c.c[1][1]) == Approx(2 * sigma / 80).epsilon(1e-4));
  CHECK(c.c[0][1] == Approx(0).margin(1e-12));
  // The circle's centre moved is the highlight moved the other way; the radius does nothing there.
  double centre[5][5] = {};
  centre[2][2] = centre[3][3] = sigma * sigma;
  CHECK(trace(propagate(s, 300, 200, centre, nullptr)) == Approx(trace(c)).epsilon(1e-4));
  double radius[5][5] = {};
  radius[4][4] = 4;
  CHECK(trace(propagate(s, 300, 200, radius, nullptr)) == Approx(0).margin(1e-12));
}

TEST_CASE("orthographic: away from the centre, radial 2 d / (r cos t), across 2 cos t d / r, radius 2 tan t dr / r") {
  // The normal at angle t from the view axis (highlight at r sin t from the centre, to the right):
  // L at 2t. A radial move d turns t by d / (r cos t); a move across turns the azimuth by
  // d / (r sin t), which moves L by sin(2t) times that; a radius dr moves sin t by -sin t dr / r.
  const double r = 100, t = 0.5;
  const DetectedSphere s{400, 300, r, 1};
  const double hx = 400 + r * std::sin(t), hy = 300, d = 0.5;
  double radial[5][5] = {}, across[5][5] = {}, radius[5][5] = {};
  radial[0][0] = d * d;
  across[1][1] = d * d;
  radius[4][4] = d * d;
  const std::array<double, 3> inPlane = {std::cos(2 * t), 0, -std::sin(2 * t)}, up = {0, 1, 0};
  const LightCovariance a = propagate(s, hx, hy, radial, nullptr);
  CHECK(a.direction[0] == Approx(std::sin(2 * t)));
  CHECK(sigmaAlong(a, inPlane) == Approx(2 * d / (r * std::cos(t))).epsilon(1e-4));
  CHECK(sigmaAlong(a, up) == Approx(0).margin(1e-9));
  CHECK(sigmaAlong(propagate(s, hx, hy, across, nullptr), up) == Approx(2 * std::cos(t) * d / r).epsilon(1e-4));
  CHECK(sigmaAlong(propagate(s, hx, hy, radius, nullptr), inPlane) == Approx(2 * std::tan(t) * d / r).epsilon(1e-4));
}

TEST_CASE("perspective: with a long lens the propagation is the orthographic one") {
  const DetectedSphere s{1500, 700, 90, 1};
  double in[5][5] = {};
  in[0][0] = in[1][1] = 1;
  in[4][4] = 0.25;
  const LightCovariance o = propagate(s, 1530, 660, in, nullptr);
  const CameraIntrinsics camera{50000, 0.006, 1000, 700};
  const LightCovariance p = propagate(s, 1530, 660, in, &camera);
  CHECK(trace(p) == Approx(trace(o)).epsilon(1e-3));
  // A short lens sees the same sphere under another angle: not the same numbers, same order.
  const CameraIntrinsics wide{24, 0.006, 1000, 700};
  CHECK(trace(propagate(s, 1530, 660, in, &wide)) == Approx(trace(o)).epsilon(0.3));
}

TEST_CASE("the 95 % radius of a 2D Gaussian: 2.448 sigma round, 1.960 sigma along a line") {
  const double round[2][2] = {{4, 0}, {0, 4}};
  CHECK(gaussianRadius(round, 0.95) == Approx(2 * std::sqrt(-2 * std::log(0.05))).epsilon(1e-6));
  CHECK(gaussianRadius(round, 0.5) == Approx(2 * std::sqrt(-2 * std::log(0.5))).epsilon(1e-6));
  const double line[2][2] = {{1e-14, 0}, {0, 9}};
  CHECK(gaussianRadius(line, 0.95) == Approx(3 * 1.959964).epsilon(1e-3));
  // Rotating the covariance changes nothing.
  const double c = std::cos(0.3), sn = std::sin(0.3);
  const double rotated[2][2] = {{9 * sn * sn + 1 * c * c, (9 - 1) * c * sn}, {(9 - 1) * c * sn, 9 * c * c + 1 * sn * sn}};
  const double diagonal[2][2] = {{1, 0}, {0, 9}};
  CHECK(gaussianRadius(rotated, 0.95) == Approx(gaussianRadius(diagonal, 0.95)).epsilon(1e-6));
}

TEST_CASE("a circle and a highlight given by hand are taken at the hand's error, not at zero") {
  DetectedSphere s{300, 200, 80, 1};
  s.byHand = true;
  double centre = 0, radius = 0;
  circleSigmas(s, centre, radius);
  CHECK(centre == LightUncertaintyModel::kHandPx);
  CHECK(radius == LightUncertaintyModel::kHandPx);
  double h[2][2];
  highlightCovariance(highlightAt(310, 190, HighlightFlag::Manual), s, h);
  CHECK(h[0][0] == Approx(LightUncertaintyModel::kHandPx * LightUncertaintyModel::kHandPx));
  CHECK(h[0][1] == 0);
  // A refined circle's own standard errors are used when it has them.
  s.centreSigmaPx = 0.2;
  s.radiusSigmaPx = 0.1;
  circleSigmas(s, centre, radius);
  CHECK(centre == Approx(0.2 * LightUncertaintyModel::kCircleFactor));
  // By hand, the bound at the centre: 1.5 px on the highlight and on the circle's centre, 2 px
  // of the radius: about sqrt(2) * 2 * 1.5 / 80 rad per axis, with the floor.
  s.centreSigmaPx = s.radiusSigmaPx = 0;
  const double deg = lightUncertaintyDeg({{s, highlightAt(300, 200, HighlightFlag::Manual)}}, nullptr);
  const double axis = std::hypot(std::sqrt(2.0) * 2 * 1.5 / 80, LightUncertaintyModel::kFloorDeg * M_PI / 180);
  CHECK(deg == Approx(LightUncertaintyModel::kScale * 2.4477 * axis * 180 / M_PI).epsilon(1e-3));
}

TEST_CASE("an asymmetric or doubtful highlight widens the bound, a round one's size does not") {
  const DetectedSphere s{300, 200, 80, 1};
  Highlight round = highlightAt(320, 190);
  round.covXX = round.covYY = 4;
  Highlight larger = round;
  larger.covXX = larger.covYY = 40;
  Highlight streak = round;
  streak.covXX = 40;
  const double base = lightUncertaintyDeg({{s, round}}, nullptr);
  CHECK(lightUncertaintyDeg({{s, larger}}, nullptr) == Approx(base).epsilon(1e-9));
  CHECK(lightUncertaintyDeg({{s, streak}}, nullptr) > base * 1.5);
  Highlight doubtful = streak;
  doubtful.confidence = 0.5;
  CHECK(lightUncertaintyDeg({{s, doubtful}}, nullptr) > lightUncertaintyDeg({{s, streak}}, nullptr) * 1.5);
}

TEST_CASE("two spheres that disagree by a few degrees widen the bound to at least their spread") {
  // Two spheres, the same highlight offset on each: they agree. Move one highlight so that its
  // light turns by about 2 d / r = 4 degrees: the mean is 2 degrees from each.
  const DetectedSphere a{200, 200, 80, 1}, b{600, 200, 80, 1};
  const double agree = lightUncertaintyDeg({{a, highlightAt(210, 195)}, {b, highlightAt(610, 195)}}, nullptr);
  const double d = 80 * 4 * M_PI / 180 / 2;
  const double disagree =
      lightUncertaintyDeg({{a, highlightAt(210, 195)}, {b, highlightAt(610 + d, 195)}}, nullptr);
  CHECK(disagree > agree);
  CHECK(disagree >= 2.0);  // the true light may be either sphere's
}
