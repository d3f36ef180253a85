#include "hrti/light_uncertainty.h"

#include <algorithm>
#include <cmath>

#include "core/error.h"

namespace surrogate::hrti {

namespace {

using M = LightUncertaintyModel;
using Vec = std::array<double, 3>;

constexpr double kDeg = M_PI / 180;

Vec lightOf(const DetectedSphere& s, double hx, double hy, const CameraIntrinsics* camera) {
  const LightDirection l = camera ? lightFromHighlightPerspective(s, hx, hy, *camera) : lightFromHighlight(s, hx, hy);
  return {l.x, l.y, l.z};
}

double dot(const Vec& a, const Vec& b) { return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]; }

// Adds J S J^T to c (2x2), J the 2x5 Jacobian on the tangent plane, S the inputs' 5x5 covariance.
void addPropagated(const double j[2][5], const double s[5][5], double weight, double c[2][2]) {
  for (int a = 0; a < 2; ++a)
    for (int b = 0; b < 2; ++b) {
      double v = 0;
      for (int p = 0; p < 5; ++p)
        for (int q = 0; q < 5; ++q) v += j[a][p] * s[p][q] * j[b][q];
      c[a][b] += weight * v;
    }
}

double rmsDeg(const double c[2][2]) { return std::sqrt(std::max(0.0, (c[0][0] + c[1][1]) / 2)) / kDeg; }

// The Jacobian (2x5) of the normalised sum's direction with respect to one sphere's hx, hy,
// cx, cy, r, on the basis e1, e2: central differences a twentieth of a pixel apart; the
// derivative of sum / |sum| is the tangent part of d(L_k) / |sum|.
void jacobian(const DetectedSphere& s, double hx, double hy, const CameraIntrinsics* camera, double norm,
              const Vec& e1, const Vec& e2, double j[2][5]) {
  const double step = 0.05;
  for (int p = 0; p < 5; ++p) {
    double plus[5] = {hx, hy, s.cx, s.cy, s.r}, minus[5] = {hx, hy, s.cx, s.cy, s.r};
    plus[p] += step;
    minus[p] -= step;
    DetectedSphere sp = s, sm = s;
    sp.cx = plus[2], sp.cy = plus[3], sp.r = plus[4];
    sm.cx = minus[2], sm.cy = minus[3], sm.r = minus[4];
    const Vec a = lightOf(sp, plus[0], plus[1], camera), b = lightOf(sm, minus[0], minus[1], camera);
    Vec d;
    for (int i = 0; i < 3; ++i) d[i] = (a[i] - b[i]) / (2 * step) / norm;
    j[0][p] = dot(d, e1);
    j[1][p] = dot(d, e2);
  }
}

}  // namespace

void tangentBasis(const Vec& l, Vec& e1, Vec& e2) {
  // The axis least aligned with l, crossed with it.
  const Vec a = std::fabs(l[0]) < 0.9 ? Vec{1, 0, 0} : Vec{0, 1, 0};
  e1 = {l[1] * a[2] - l[2] * a[1], l[2] * a[0] - l[0] * a[2], l[0] * a[1] - l[1] * a[0]};
  const double n = std::sqrt(e1[0] * e1[0] + e1[1] * e1[1] + e1[2] * e1[2]);
  for (double& v : e1) v /= n;
  e2 = {l[1] * e1[2] - l[2] * e1[1], l[2] * e1[0] - l[0] * e1[2], l[0] * e1[1] - l[1] * e1[0]};
}


LightCovariance propagate(const DetectedSphere& sphere, double hx, double hy, const double inputs[5][5],
                          const CameraIntrinsics* camera) {
  LightCovariance out;
  out.direction = lightOf(sphere, hx, hy, camera);
  Vec e1, e2;
  tangentBasis(out.direction, e1, e2);
  double j[2][5];
  jacobian(sphere, hx, hy, camera, 1, e1, e2, j);
  addPropagated(j, inputs, 1, out.c);
  return out;
}

void highlightCovariance(const Highlight& h, const DetectedSphere& sphere, double out[2][2]) {
  (void)sphere;
  if (h.flag == HighlightFlag::Manual) {
    out[0][0] = out[1][1] = M::kHandPx * M::kHandPx;
    out[0][1] = out[1][0] = 0;
    return;
  }
  double sxx = h.covXX, sxy = h.covXY, syy = h.covYY;
  if (!(sxx > 0 && syy > 0)) {
    // Not measured: the core as an ellipse of its area, fill and elongation (E = sqrt(l2 / l1),
    // 4 pi sqrt(l1 l2) fill = area), its orientation unknown: isotropic with its larger axis.
    const double geometric = h.measures.area / (4 * M_PI * std::max(0.3, h.measures.fill));
    const double e = std::clamp(h.measures.elongation, 0.1, 1.0);
    sxx = syy = geometric / e;
    sxy = 0;
  }
  const double mean = (sxx + syy) / 2, det = sxx * syy - sxy * sxy;
  const double l2 = std::max(0.0, mean - std::sqrt(std::max(0.0, mean * mean - det)));
  const double a2 = M::kAsymmetry * M::kAsymmetry, s2 = M::kSpread * M::kSpread;
  const double m2 = M::kMinHighlightPx * M::kMinHighlightPx;
  out[0][0] = a2 * (sxx - l2) + s2 * sxx + m2;
  out[1][1] = a2 * (syy - l2) + s2 * syy + m2;
  out[0][1] = out[1][0] = (a2 + s2) * sxy;
  // A doubtful highlight: its centre may be on the wrong part of what was taken (a streak, a
  // second spot), so its variance grows as the confidence falls (4x at 0.5).
  const double doubt = 1 / std::max(0.25, h.confidence);
  for (int a = 0; a < 2; ++a)
    for (int b = 0; b < 2; ++b) out[a][b] *= doubt * doubt;
}

void circleSigmas(const DetectedSphere& sphere, double& centrePx, double& radiusPx) {
  if (sphere.centreSigmaPx > 0 || sphere.radiusSigmaPx > 0) {
    centrePx = M::kCircleFactor * sphere.centreSigmaPx;
    radiusPx = M::kCircleFactor * sphere.radiusSigmaPx;
  } else if (sphere.byHand) {
    centrePx = radiusPx = M::kHandPx;
  } else {
    centrePx = radiusPx = M::kCircleShare * sphere.r;
  }
}

LightCovariance lightCovariance(const std::vector<SphereEvidence>& evidence, const CameraIntrinsics* camera) {
  if (evidence.empty()) throw Error(ErrorKind::Internal, "", "light directions", "a light's uncertainty without evidence");
  std::vector<Vec> perSphere;
  Vec sum{0, 0, 0};
  for (const SphereEvidence& e : evidence) {
    perSphere.push_back(lightOf(e.sphere, e.highlight.x, e.highlight.y, camera));
    for (int k = 0; k < 3; ++k) sum[k] += perSphere.back()[k];
  }
  const double norm = std::sqrt(dot(sum, sum));
  LightCovariance out;
  for (int k = 0; k < 3; ++k) out.direction[k] = sum[k] / norm;
  Vec e1, e2;
  tangentBasis(out.direction, e1, e2);
  double highlight[2][2] = {{0, 0}, {0, 0}}, circle[2][2] = {{0, 0}, {0, 0}}, spread[2][2] = {{0, 0}, {0, 0}};
  for (std::size_t k = 0; k < evidence.size(); ++k) {
    const DetectedSphere& s = evidence[k].sphere;
    const Highlight& h = evidence[k].highlight;
    double j[2][5];
    jacobian(s, h.x, h.y, camera, norm, e1, e2, j);
    double hc[2][2];
    highlightCovariance(h, s, hc);
    double centrePx = 0, radiusPx = 0;
    circleSigmas(s, centrePx, radiusPx);
    double sh[5][5] = {}, sc[5][5] = {};
    sh[0][0] = hc[0][0], sh[0][1] = hc[0][1], sh[1][0] = hc[1][0], sh[1][1] = hc[1][1];
    sc[2][2] = sc[3][3] = centrePx * centrePx;
    sc[4][4] = radiusPx * radiusPx;
    addPropagated(j, sh, 1, highlight);
    addPropagated(j, sc, 1, circle);
  }
  if (evidence.size() >= 2) {
    // The spheres' spread about their mean: the sample covariance of the mean of n directions.
    const double n = static_cast<double>(evidence.size());
    for (const Vec& l : perSphere) {
      const double t1 = dot(l, e1), t2 = dot(l, e2);
      spread[0][0] += t1 * t1 / (n * (n - 1));
      spread[0][1] += t1 * t2 / (n * (n - 1));
      spread[1][1] += t2 * t2 / (n * (n - 1));
    }
    spread[1][0] = spread[0][1];
  }
  const double floor = M::kFloorDeg * kDeg;
  for (int a = 0; a < 2; ++a)
    for (int b = 0; b < 2; ++b)
      out.c[a][b] = highlight[a][b] + circle[a][b] + spread[a][b] + (a == b ? floor * floor : 0);
  out.highlightDeg = rmsDeg(highlight);
  out.circleDeg = rmsDeg(circle);
  out.spreadDeg = rmsDeg(spread);
  return out;
}

namespace {

constexpr int kRadiusSteps = 512;     // points of gaussianRadius's midpoint rule
constexpr int kRadiusBisections = 60;  // its bisection steps

// The midpoint rule's nodes u_i = -pi/2 + (i + 1/2) pi / n, the same for every covariance and
// radius: their sines and cosines computed once (the same doubles each time, so the integral
// is the same bits). `mirror[i]` is the node whose sine is -sin(u_i) and cosine cos(u_i) to the
// bit, if any (u_{n-1-i}, where rounding allows): its term of the integrand is then the same
// double, t sin u only changing sign, and is computed once.
struct RadiusNodes {
  double sinU[kRadiusSteps], cosU[kRadiusSteps];
  int mirror[kRadiusSteps];
};

const RadiusNodes& radiusNodes() {
  static const RadiusNodes nodes = [] {
    RadiusNodes n{};
    for (int i = 0; i < kRadiusSteps; ++i) {
      const double u = -M_PI / 2 + (i + 0.5) * M_PI / kRadiusSteps;
      n.sinU[i] = std::sin(u);
      n.cosU[i] = std::cos(u);
    }
    for (int i = 0; i < kRadiusSteps; ++i) {
      const int j = kRadiusSteps - 1 - i;
      n.mirror[i] = j < i && n.sinU[j] == -n.sinU[i] && n.cosU[j] == n.cosU[i] ? j : -1;
    }
    return n;
  }();
  return nodes;
}

}  // namespace

double gaussianRadius(const double c[2][2], double p) {
  // Along the eigenvectors (variances l1 >= l2): P(|X| <= t) = integral over x in [-t, t] of the
  // normal density of x (variance l1) times P(|Y| <= sqrt(t^2 - x^2)) = erf(sqrt(t^2 - x^2) /
  // sqrt(2 l2)); with x = t sin u the integrand is smooth (midpoint rule), and as l2 -> 0 it
  // tends to erf(t / sqrt(2 l1)). Solved for t by bisection. What does not depend on t (the
  // nodes, the square roots) is computed once, as the same operations on the same operands:
  // the radius is the same bits as when each step computed them (-ffp-contract=off,
  // CMakeLists.txt).
  const double mean = (c[0][0] + c[1][1]) / 2;
  const double det = c[0][0] * c[1][1] - c[0][1] * c[1][0];
  const double diff = std::sqrt(std::max(0.0, mean * mean - det));
  const double l1 = mean + diff, l2 = std::max(0.0, mean - diff);
  if (!(l1 > 0)) return 0;
  const RadiusNodes& nodes = radiusNodes();
  const double twoL1 = 2 * l1, density = std::sqrt(2 * M_PI * l1);
  const double acrossScale = l2 > 0 ? std::sqrt(2 * l2) : 0;
  double term[kRadiusSteps];
  auto probability = [&](double t) {
    double sum = 0;
    for (int i = 0; i < kRadiusSteps; ++i) {
      if (nodes.mirror[i] >= 0) {
        term[i] = term[nodes.mirror[i]];
      } else {
        const double x = t * nodes.sinU[i], y = t * nodes.cosU[i];
        const double across = l2 > 0 ? std::erf(y / acrossScale) : 1.0;
        term[i] = std::exp(-x * x / twoL1) / density * across * t * nodes.cosU[i];
      }
      sum += term[i];  // in node order, as before
    }
    return sum * M_PI / kRadiusSteps;
  };
  double lo = 0, hi = 4 * std::sqrt(l1 + l2);  // P(|X| <= 4 sqrt(trace)) > 0.999
  // Once lo and hi are neighbouring doubles the midpoint repeats: its probability is kept.
  double lastMid = -1, lastProbability = 0;
  for (int i = 0; i < kRadiusBisections; ++i) {
    const double mid = (lo + hi) / 2;
    if (mid != lastMid) lastProbability = probability(mid), lastMid = mid;
    (lastProbability < p ? lo : hi) = mid;
  }
  return hi;
}

double lightUncertaintyDeg(const std::vector<SphereEvidence>& evidence, const CameraIntrinsics* camera) {
  const LightCovariance c = lightCovariance(evidence, camera);
  return M::kScale * gaussianRadius(c.c, 0.95) / kDeg;
}

}  // namespace surrogate::hrti
