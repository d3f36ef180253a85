#include "hrti/light_position.h"

#include <Eigen/Dense>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>
#include <utility>

#include "core/error.h"

namespace surrogate::hrti {

LightPosition lightPositionFromSpheres(const std::vector<SphereGeometry>& spheres,
                                       const std::vector<Highlight>& highlights,
                                       const CameraIntrinsics& camera) {
  if (spheres.size() < 2 || spheres.size() != highlights.size())
    throw Error(ErrorKind::Internal, "", "light position", "needs two or more spheres with one highlight each");
  Eigen::Matrix3d a = Eigen::Matrix3d::Zero();
  Eigen::Vector3d rhs = Eigen::Vector3d::Zero(), meanPoint = Eigen::Vector3d::Zero(), meanDir = Eigen::Vector3d::Zero();
  std::vector<Eigen::Vector3d> points, dirs;
  for (std::size_t k = 0; k < spheres.size(); ++k) {
    const double radius = spheres[k].diameterMm / 2;
    double c[3], d[3];
    sphereCentre(spheres[k].sphere, camera, radius, c);
    pixelRay(camera, highlights[k].x, highlights[k].y, d);
    const Eigen::Vector3d centre(c[0], c[1], c[2]), ray(d[0], d[1], d[2]);
    const double b = ray.dot(centre), cc = centre.squaredNorm() - radius * radius;
    const double t = b - std::sqrt(std::max(0.0, b * b - cc));
    const Eigen::Vector3d p = t * ray;
    const Eigen::Vector3d n = (p - centre).normalized(), v = -ray;
    const Eigen::Vector3d l = (2 * n.dot(v) * n - v).normalized();
    const Eigen::Matrix3d proj = Eigen::Matrix3d::Identity() - l * l.transpose();
    a += proj;
    rhs += proj * p;
    points.push_back(p);
    dirs.push_back(l);
    meanPoint += p;
    meanDir += l;
  }
  meanPoint /= double(spheres.size());
  meanDir.normalize();
  LightPosition out;
  const Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> eig(a);
  const double smallest = eig.eigenvalues()(0), largest = eig.eigenvalues()(2);
  Eigen::Vector3d x;
  if (smallest < 1e-4 * largest) {
    out.nearParallel = true;
    x = meanPoint + 10000.0 * meanDir;
  } else {
    x = a.ldlt().solve(rhs);
  }
  double sum = 0;
  for (std::size_t k = 0; k < points.size(); ++k) {
    const Eigen::Vector3d w = x - points[k];
    sum += (w - w.dot(dirs[k]) * dirs[k]).squaredNorm();
  }
  out.x = x(0);
  out.y = x(1);
  out.z = x(2);
  out.residualMm = std::sqrt(sum / points.size());
  return out;
}

}  // namespace surrogate::hrti

// ---- Near lights in frame coordinates (light_position.h, second part)

namespace surrogate::hrti {

namespace {

constexpr double kDeg = M_PI / 180;
constexpr int kParams = 7;  // per sphere: hx, hy, cx, cy, r, and two angles turning its ray

struct Ray {
  Eigen::Vector3d p, l;
};

Eigen::Vector3d eig(const Vec3& v) { return {v[0], v[1], v[2]}; }
Vec3 arr(const Eigen::Vector3d& v) { return {v(0), v(1), v(2)}; }

// A fixed basis of the plane across each nominal ray: the floor's two angles turn the ray
// along it (small angles: l + a1 e1 + a2 e2, normalised).
struct Across {
  Eigen::Vector3d e1, e2;
};

Ray rayOf(const double* q, int width, int height, const Across& across) {
  DetectedSphere s;
  s.cx = q[2], s.cy = q[3], s.r = q[4];
  Vec3 p, l;
  mirrorRay(s, q[0], q[1], width, height, p, l);
  Ray ray{eig(p), eig(l)};
  ray.l = (ray.l + q[5] * across.e1 + q[6] * across.e2).normalized();
  return ray;
}

// The point nearest to the rays (least squares); false when they are parallel.
bool nearest(const std::vector<Ray>& rays, Eigen::Vector3d& x) {
  Eigen::Matrix3d a = Eigen::Matrix3d::Zero();
  Eigen::Vector3d rhs = Eigen::Vector3d::Zero();
  for (const Ray& r : rays) {
    const Eigen::Matrix3d proj = Eigen::Matrix3d::Identity() - r.l * r.l.transpose();
    a += proj;
    rhs += proj * r.p;
  }
  const Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> e(a);
  // Two rays at an angle u give a smallest eigenvalue of about u^2 / 2: 1e-12 is u ~ 1.4e-6 rad,
  // where no measured pair of highlights comes (their noise alone turns a ray by 1e-3).
  if (!(e.eigenvalues()(0) > 1e-12 * e.eigenvalues()(2))) return false;
  x = a.ldlt().solve(rhs);
  return true;
}

// The signed distance between rays i and j at their closest (along li x lj; unsigned when parallel).
double miss(const Ray& a, const Ray& b) {
  const Eigen::Vector3d n = a.l.cross(b.l), d = b.p - a.p;
  if (n.norm() < 1e-12) return (d - d.dot(a.l) * a.l).norm();
  return d.dot(n) / n.norm();
}

std::vector<std::pair<int, int>> pairsOf(int n) {
  std::vector<std::pair<int, int>> out;
  for (int i = 0; i < n; ++i)
    for (int j = i + 1; j < n; ++j) out.push_back({i, j});
  return out;
}

// X (3) then each pair's signed miss, from all spheres' parameters; false when parallel.
bool outputsOf(const std::vector<double>& q, int n, int width, int height, const std::vector<Across>& across,
               Eigen::VectorXd& y) {
  std::vector<Ray> rays;
  for (int k = 0; k < n; ++k) rays.push_back(rayOf(&q[k * kParams], width, height, across[k]));
  Eigen::Vector3d x;
  if (!nearest(rays, x)) return false;
  const auto pairs = pairsOf(n);
  y.resize(3 + static_cast<int>(pairs.size()));
  y.head<3>() = x;
  for (std::size_t i = 0; i < pairs.size(); ++i) y(3 + i) = miss(rays[pairs[i].first], rays[pairs[i].second]);
  return true;
}

std::string shown(double v, int decimals) {
  char buf[64];
  std::snprintf(buf, sizeof buf, "%.*f", decimals, v);
  return buf;
}

std::string namesOf(const std::vector<int>& numbers) {
  if (numbers.size() == 2) return "spheres " + std::to_string(numbers[0]) + " and " + std::to_string(numbers[1]);
  std::string s = "spheres ";
  for (std::size_t k = 0; k < numbers.size(); ++k)
    s += (k == 0 ? "" : k + 1 == numbers.size() ? " and " : ", ") + std::to_string(numbers[k]);
  return s;
}

}  // namespace

Vec3 sphereCentreInFrame(const DetectedSphere& sphere, int width, int height) {
  return {sphere.cx - (width - 1) / 2.0, (height - 1) / 2.0 - sphere.cy, sphere.r};
}

void mirrorRay(const DetectedSphere& sphere, double hx, double hy, int width, int height, Vec3& point,
               Vec3& direction) {
  const double nx = (hx - sphere.cx) / sphere.r, ny = -(hy - sphere.cy) / sphere.r;
  const double nz = std::sqrt(std::max(0.0, 1 - nx * nx - ny * ny));
  const Vec3 c = sphereCentreInFrame(sphere, width, height);
  point = {c[0] + sphere.r * nx, c[1] + sphere.r * ny, c[2] + sphere.r * nz};
  direction = {2 * nz * nx, 2 * nz * ny, 2 * nz * nz - 1};
}

NearLightPosition positionFromSpheres(const std::vector<SphereEvidence>& evidence, int width, int height,
                                      const std::vector<int>& sphereNumbers) {
  std::vector<std::array<std::array<double, 5>, 5>> inputs;
  for (const SphereEvidence& e : evidence) {
    std::array<std::array<double, 5>, 5> s{};
    double hc[2][2];
    highlightCovariance(e.highlight, e.sphere, hc);
    double centrePx = 0, radiusPx = 0;
    circleSigmas(e.sphere, centrePx, radiusPx);
    s[0][0] = hc[0][0], s[0][1] = hc[0][1], s[1][0] = hc[1][0], s[1][1] = hc[1][1];
    s[2][2] = s[3][3] = centrePx * centrePx;
    s[4][4] = radiusPx * radiusPx;
    inputs.push_back(s);
  }
  return positionFromSpheres(evidence, width, height, inputs, LightUncertaintyModel::kFloorDeg, sphereNumbers);
}

NearLightPosition positionFromSpheres(const std::vector<SphereEvidence>& evidence, int width, int height,
                                      const std::vector<std::array<std::array<double, 5>, 5>>& inputs,
                                      double floorDeg, const std::vector<int>& sphereNumbers) {
  const int n = static_cast<int>(evidence.size());
  if (n < 2 || inputs.size() != evidence.size() || (!sphereNumbers.empty() && sphereNumbers.size() != evidence.size()))
    throw Error(ErrorKind::Internal, "", "light positions", "a light's position needs two or more spheres, each with its inputs' covariance");
  std::vector<int> numbers = sphereNumbers;
  if (numbers.empty())
    for (int k = 0; k < n; ++k) numbers.push_back(k);
  const std::string names = namesOf(numbers);

  std::vector<double> q(static_cast<std::size_t>(n) * kParams, 0.0);
  std::vector<Across> across(n);
  std::vector<Ray> rays;
  Eigen::Vector3d meanDirection = Eigen::Vector3d::Zero();
  for (int k = 0; k < n; ++k) {
    const SphereEvidence& e = evidence[k];
    double* p = &q[k * kParams];
    p[0] = e.highlight.x, p[1] = e.highlight.y, p[2] = e.sphere.cx, p[3] = e.sphere.cy, p[4] = e.sphere.r;
    Vec3 point, l;
    mirrorRay(e.sphere, p[0], p[1], width, height, point, l);
    Vec3 e1, e2;
    tangentBasis(l, e1, e2);
    across[k] = {eig(e1), eig(e2)};
    rays.push_back({eig(point), eig(l)});
    meanDirection += eig(l);
  }
  NearLightPosition out;
  const auto pairs = pairsOf(n);
  for (const auto& [i, j] : pairs) {
    const double angle = std::acos(std::clamp(rays[i].l.dot(rays[j].l), -1.0, 1.0)) / kDeg;
    out.meetAngleDeg = std::max(out.meetAngleDeg, angle);
  }
  Eigen::VectorXd y;
  if (!outputsOf(q, n, width, height, across, y)) {
    out.direction = arr(meanDirection.normalized());
    out.reason = "the rays from " + names + " are parallel (they meet at " + shown(out.meetAngleDeg, 2) +
                 " degrees): the light is too far to place from them, as if at infinity";
    out.summary = out.reason;
    return out;
  }
  const Eigen::Vector3d x = y.head<3>();
  out.position = arr(x);
  out.distancePx = x.norm();
  const Eigen::Vector3d u = x.normalized();
  out.direction = arr(u);

  // The Jacobian of y by central differences: a twentieth of a pixel, a ten-thousandth of a
  // radian for the floor's angles (the model is smooth at both scales).
  const int m = static_cast<int>(y.size());
  Eigen::MatrixXd jac = Eigen::MatrixXd::Zero(m, n * kParams);
  bool jacobianOk = true;
  for (int c = 0; c < n * kParams; ++c) {
    const double step = c % kParams < 5 ? 0.05 : 1e-4;
    std::vector<double> plus = q, minus = q;
    plus[c] += step;
    minus[c] -= step;
    Eigen::VectorXd a, b;
    if (!outputsOf(plus, n, width, height, across, a) || !outputsOf(minus, n, width, height, across, b)) {
      jacobianOk = false;
      break;
    }
    jac.col(c) = (a - b) / (2 * step);
  }
  Eigen::MatrixXd s = Eigen::MatrixXd::Zero(n * kParams, n * kParams);
  const double floor2 = (floorDeg * kDeg) * (floorDeg * kDeg);
  for (int k = 0; k < n; ++k) {
    for (int a = 0; a < 5; ++a)
      for (int b = 0; b < 5; ++b) s(k * kParams + a, k * kParams + b) = inputs[k][a][b];
    s(k * kParams + 5, k * kParams + 5) = s(k * kParams + 6, k * kParams + 6) = floor2;
  }
  const Eigen::MatrixXd cov = jac * s * jac.transpose();
  for (int a = 0; a < 3; ++a)
    for (int b = 0; b < 3; ++b) out.covariance[a][b] = cov(a, b);
  const Eigen::Matrix3d cx = cov.topLeftCorner<3, 3>();
  // |X| is a 1D Gaussian about |X_true| along u: 1.960 sigma; X / |X| a 2D one across u.
  out.distanceBoundPx = 1.959964 * std::sqrt(std::max(0.0, u.dot(cx * u)));
  Vec3 e1, e2;
  tangentBasis(out.direction, e1, e2);
  const Eigen::Vector3d t1 = eig(e1), t2 = eig(e2);
  const double d2 = out.distancePx * out.distancePx;
  const double c2[2][2] = {{t1.dot(cx * t1) / d2, t1.dot(cx * t2) / d2}, {t2.dot(cx * t1) / d2, t2.dot(cx * t2) / d2}};
  out.directionBoundDeg = gaussianRadius(c2, 0.95) / kDeg;
  // The pair whose miss is the largest share of what its inputs allow.
  double worstRatio = -1;
  for (std::size_t i = 0; i < pairs.size(); ++i) {
    const double bound = NearLightRule::kMaxMissSigmas * std::sqrt(std::max(0.0, cov(3 + i, 3 + i)));
    const double ratio = std::fabs(y(3 + i)) / std::max(bound, 1e-12);
    if (ratio > worstRatio) {
      worstRatio = ratio;
      out.missPx = std::fabs(y(3 + i));
      out.missBoundPx = bound;
    }
  }

  // The verdict, the first failing reason in this order.
  double behind = 0;
  int behindSphere = -1;
  for (int k = 0; k < n; ++k) {
    const double t = (x - rays[k].p).dot(rays[k].l);
    if (t < behind) behind = t, behindSphere = k;
  }
  const double relative = out.distanceBoundPx / out.distancePx;
  const std::string meet = "the rays from " + names + " meet at " + shown(out.meetAngleDeg, 1) + " degrees";
  if (behindSphere >= 0) {
    out.reason = "the rays from " + names + " (at " + shown(out.meetAngleDeg, 1) +
                 " degrees) diverge: they come nearest to each other behind sphere " +
                 std::to_string(numbers[behindSphere]) +
                 ", so the light is too far to place from them (a distant or grazing light, or spheres too close together)";
  } else if (x(2) < 0) {
    out.reason = meet + " below the object's plane (" + shown(-x(2), 0) +
                 " px under it): a highlight is not where the light's reflection is";
  } else if (!jacobianOk) {
    out.reason = meet + ", too nearly parallel to tell how far the light's position can be trusted";
  } else if (out.missPx > out.missBoundPx) {
    out.reason = "the rays from " + names + " miss each other by " + shown(out.missPx, 1) + " px where their highlights and circles allow " +
                 shown(out.missBoundPx, 1) + " px: a highlight is not where the light's reflection is";
  } else if (relative > NearLightRule::kMaxRelativeBound) {
    out.reason = meet + ": too parallel to place the light (a grazing light or spheres too close together); its distance of " +
                 shown(out.distancePx, 0) + " px is known only to +-" + shown(out.distanceBoundPx, 0) + " px (" +
                 shown(100 * relative, 0) + " %, 95 % bound), over the " + shown(100 * NearLightRule::kMaxRelativeBound, 0) +
                 " % allowed";
  }
  out.trusted = out.reason.empty();
  out.summary = "distance " + shown(out.distancePx, 0) + " px +-" + shown(out.distanceBoundPx, 0) + " px (" +
                shown(100 * relative, 1) + " %, 95 %), direction +-" + shown(out.directionBoundDeg, 2) + " degrees; " +
                meet + " and miss by " + shown(out.missPx, 1) + " px (allowed " + shown(out.missBoundPx, 1) + " px)";
  return out;
}

PositionAtDistance positionAtDistance(const DetectedSphere& sphere, const Vec3& direction, double distancePx,
                                      int width, int height) {
  PositionAtDistance out;
  const Eigen::Vector3d l = eig(direction).normalized();
  const Eigen::Vector3d h = l + Eigen::Vector3d(0, 0, 1);
  if (!(distancePx > 0) || h.norm() < 1e-9 || !std::isfinite(l.norm())) {
    out.reason = !(distancePx > 0) ? "the stated light distance is not a positive length"
                                   : "the light's direction points away from the camera: no highlight on a sphere gives it";
    return out;
  }
  const Eigen::Vector3d p = eig(sphereCentreInFrame(sphere, width, height)) + sphere.r * h.normalized();
  const double b = p.dot(l), pp = p.squaredNorm(), d2 = distancePx * distancePx;
  if (d2 < pp) {
    out.reason = "the stated light distance (" + shown(distancePx, 0) + " px, " + shown(distancePx / width, 2) +
                 " frame widths) is shorter than the distance of the sphere at (" + shown(sphere.cx, 0) + ", " +
                 shown(sphere.cy, 0) + ") from the frame's centre (" + shown(std::sqrt(pp), 0) +
                 " px): the light cannot be that close; check the stated distance";
    return out;
  }
  const double t = -b + std::sqrt(b * b - pp + d2);
  out.position = arr(p + t * l);
  out.ok = true;
  return out;
}

Vec3 directionOfPosition(const Vec3& position) {
  const double n = std::sqrt(position[0] * position[0] + position[1] * position[1] + position[2] * position[2]);
  if (!(n > 0) || !std::isfinite(n))
    throw Error(ErrorKind::Internal, "", "light positions", "a light at the frame's centre (or not finite) has no direction");
  return {position[0] / n, position[1] / n, position[2] / n};
}

Vec3 positionOfDirection(const Vec3& direction, double distancePx) {
  return {direction[0] * distancePx, direction[1] * distancePx, direction[2] * distancePx};
}

}  // namespace surrogate::hrti
