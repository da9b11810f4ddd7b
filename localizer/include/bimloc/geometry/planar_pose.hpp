// A pose in the plane of a storey (x, y and the heading about z) from a 3D pose: what the
// filter estimates, what the bench scores and draws.
#pragma once

#include <Eigen/Geometry>
#include <cmath>

namespace bimloc {

// The heading of a rotation: the angle of its x axis in the xy plane.
inline double yawOf(const Eigen::Matrix3d& R) { return std::atan2(R(1, 0), R(0, 0)); }

// x, y, yaw.
inline Eigen::Vector3d planarPose(const Eigen::Isometry3d& T) {
  return {T.translation().x(), T.translation().y(), yawOf(T.linear())};
}

}  // namespace bimloc
