#include <catch2/catch.hpp>

#include <cmath>

#include "hrti/light_direction.h"
#include "hrti/light_position.h"

using namespace surrogate::hrti;

TEST_CASE("a highlight at the sphere's centre means a light at the camera") {
  const LightDirection l = lightFromHighlight({100, 100, 50, 1}, 100, 100);
  CHECK(l.x == Approx(0).margin(1e-12));
  CHECK(l.y == Approx(0).margin(1e-12));
  CHECK(l.z == Approx(1));
  CHECK(l.elevationDeg == Approx(90));
}

TEST_CASE("the reflection formula: known highlight points give known lights, of unit length") {
  const DetectedSphere s{200, 150, 80, 1};
  // Normal at 45 degrees to the right: L = (2 nz nx, 2 nz ny, 2 nz^2 - 1) = (1, 0, 0).
  const double n = std::sqrt(0.5);
  LightDirection l = lightFromHighlight(s, 200 + 80 * n, 150);
  CHECK(l.x == Approx(1));
  CHECK(l.z == Approx(0).margin(1e-12));
  // Image y points down, camera Y up: a highlight above the centre is a light from the top.
  l = lightFromHighlight(s, 200, 150 - 80 * std::sin(M_PI / 8));
  CHECK(l.y > 0);
  CHECK(l.elevationDeg == Approx(45));
  CHECK(l.azimuthDeg == Approx(90));
  for (double hx = 130; hx <= 270; hx += 17)
    for (double hy = 80; hy <= 220; hy += 19) {
      if (std::hypot(hx - 200, hy - 150) >= 80) continue;
      const LightDirection q = lightFromHighlight(s, hx, hy);
      CHECK(std::sqrt(q.x * q.x + q.y * q.y + q.z * q.z) == Approx(1));
    }
}

TEST_CASE("the perspective model tends to the orthographic one as the focal length grows") {
  const DetectedSphere s{1500, 700, 90, 1};
  const LightDirection ortho = lightFromHighlight(s, 1530, 660);
  double previous = 1e9;
  for (double f : {50.0, 500.0, 5000.0, 50000.0}) {
    const LightDirection p = lightFromHighlightPerspective(s, 1530, 660, {f, 0.006, 1000, 700});
    const double angle = std::acos(std::min(1.0, p.x * ortho.x + p.y * ortho.y + p.z * ortho.z));
    CHECK(angle <= previous + 1e-12);
    previous = angle;
  }
  CHECK(previous < 1e-3);  // about (offset * pitch / f): 6e-5 rad here
}

TEST_CASE("two spheres of known size locate a near light, parallel rays are flagged") {
  // Build the scene forward: a light at X, spheres of 25 mm diameter at known 3D centres;
  // project the spheres and their highlights, then recover X.
  const CameraIntrinsics cam{50, 0.006, 1000, 750};
  const double radius = 12.5;
  auto project = [&](const double p[3], double* u, double* v) {
    *u = cam.principalX + (p[0] / -p[2]) * cam.focalLengthMm / cam.pixelPitchMm;
    *v = cam.principalY - (p[1] / -p[2]) * cam.focalLengthMm / cam.pixelPitchMm;
  };
  const double light[3] = {300, 250, -400};
  std::vector<SphereGeometry> spheres;
  std::vector<Highlight> highlights;
  for (double cx : {-150.0, 150.0}) {
    const double c[3] = {cx, 100, -1000};
    // The highlight point on the sphere: the normal bisects the directions to the camera and to
    // the light; iterate the fixed point P = C + R normalize(dirCam(P) + dirLight(P)).
    double p[3] = {c[0], c[1], c[2] + radius};
    for (int it = 0; it < 200; ++it) {
      double toCam[3], toLight[3], n[3];
      double lc = 0, ll = 0;
      for (int k = 0; k < 3; ++k) {
        toCam[k] = -p[k];
        toLight[k] = light[k] - p[k];
        lc += toCam[k] * toCam[k];
        ll += toLight[k] * toLight[k];
      }
      double nn = 0;
      for (int k = 0; k < 3; ++k) {
        n[k] = toCam[k] / std::sqrt(lc) + toLight[k] / std::sqrt(ll);
        nn += n[k] * n[k];
      }
      for (int k = 0; k < 3; ++k) p[k] = c[k] + radius * n[k] / std::sqrt(nn);
    }
    double u, v, cu, cv;
    project(p, &u, &v);
    project(c, &cu, &cv);
    // The image of a sphere off the axis is slightly elliptical; its radius along the line
    // from the principal point is what sphereCentre() inverts, so project the two tangent
    // points on that line.
    const double distance = std::sqrt(c[0] * c[0] + c[1] * c[1] + c[2] * c[2]);
    const double half = std::asin(radius / distance);
    const double centreAngle = std::atan2(std::hypot(cu - cam.principalX, cv - cam.principalY) * cam.pixelPitchMm, cam.focalLengthMm);
    const double inner = std::tan(centreAngle - half) * cam.focalLengthMm / cam.pixelPitchMm;
    const double outer = std::tan(centreAngle + half) * cam.focalLengthMm / cam.pixelPitchMm;
    const double ux = (cu - cam.principalX) / std::hypot(cu - cam.principalX, cv - cam.principalY);
    const double uy = (cv - cam.principalY) / std::hypot(cu - cam.principalX, cv - cam.principalY);
    const double mid = (inner + outer) / 2;
    DetectedSphere s{cam.principalX + mid * ux, cam.principalY + mid * uy, (outer - inner) / 2, 1};
    spheres.push_back({s, 2 * radius});
    Highlight h;
    h.x = u;
    h.y = v;
    h.flag = HighlightFlag::Ok;
    highlights.push_back(h);
  }
  const LightPosition x = lightPositionFromSpheres(spheres, highlights, cam);
  CHECK_FALSE(x.nearParallel);
  CHECK(x.x == Approx(light[0]).margin(2));
  CHECK(x.y == Approx(light[1]).margin(2));
  CHECK(x.z == Approx(light[2]).margin(2));
  CHECK(x.residualMm < 0.5);

  // The same highlight position relative to each sphere: parallel rays, a light at infinity.
  std::vector<Highlight> parallel = highlights;
  parallel[1].x = parallel[0].x - spheres[0].sphere.cx + spheres[1].sphere.cx;
  parallel[1].y = parallel[0].y - spheres[0].sphere.cy + spheres[1].sphere.cy;
  const CameraIntrinsics far{5000000, 0.006, 1000, 750};
  const LightPosition p = lightPositionFromSpheres(spheres, parallel, far);
  CHECK(p.nearParallel);
}
