// The 3D position of a light from its highlights on two or more spheres of known size
// (dissertation 6.2, future work there).
//
// With the camera's intrinsics and the real sphere diameter, each sphere's centre is known
// in millimetres (camera frame, camera at the origin); each highlight is a point P_k on its
// sphere from which the light lies along the reflected direction L_k. The light is the point
// X nearest to all rays in the least-squares sense:
//     sum_k (I - L_k L_k^T) X = sum_k (I - L_k L_k^T) P_k
// residualMm is the RMS distance from X to the rays. When the rays are nearly parallel (a
// distant or grazing light: the system is ill-conditioned) nearParallel is set and X is
// placed 10 m along the mean direction from the mean highlight point.
#pragma once

#include <vector>

#include "hrti/highlight_detection.h"
#include "hrti/light_direction.h"

namespace surrogate::hrti {

struct SphereGeometry {
  DetectedSphere sphere;
  double diameterMm = 0;
};

struct LightPosition {
  double x = 0, y = 0, z = 0;  // mm, camera frame
  double residualMm = 0;
  bool nearParallel = false;
};

LightPosition lightPositionFromSpheres(const std::vector<SphereGeometry>& spheres,
                                       const std::vector<Highlight>& perSphere,
                                       const CameraIntrinsics& camera);

}  // namespace surrogate::hrti
