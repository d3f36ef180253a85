#include "hrti/light_position.h"

#include <Eigen/Dense>

#include <cmath>

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
