// The planar-pose toolkit: a pose in the plane of a storey (x, y and the heading about z), as
// the filter estimates it, the S-Graph optimizes it and the bench scores and draws it. One
// copy of each operation for the whole project.
#pragma once

#include <Eigen/Geometry>
#include <cmath>

namespace bimloc {

// x, y, yaw (radians).
using PlanarPose = Eigen::Vector3d;

// The heading of a rotation: the angle of its x axis in the xy plane.
inline double yawOf(const Eigen::Matrix3d& R) { return std::atan2(R(1, 0), R(0, 0)); }

// The rotation without its heading: roll and pitch (R = Rz(yaw) * tilt).
inline Eigen::Matrix3d tiltOf(const Eigen::Matrix3d& R) {
  return Eigen::AngleAxisd(-yawOf(R), Eigen::Vector3d::UnitZ()).toRotationMatrix() * R;
}

// x, y, yaw of a 3D pose.
inline PlanarPose planarPose(const Eigen::Isometry3d& T) { return {T.translation().x(), T.translation().y(), yawOf(T.linear())}; }

// An angle into [-pi, pi]. The filter's inner loops call it for every particle, observation
// and landmark: a branch instead of atan2(sin, cos).
inline double wrapAngle(double a) {
  if (a > M_PI) {
    a -= 2.0 * M_PI;
    if (a > M_PI) a = std::remainder(a, 2.0 * M_PI);
  } else if (a < -M_PI) {
    a += 2.0 * M_PI;
    if (a < -M_PI) a = std::remainder(a, 2.0 * M_PI);
  }
  return a;
}

// The same for automatic differentiation (Ceres jets): smooth, no branch on the value.
template <typename T>
T wrapAngle(const T& a) {
  using std::atan2, std::cos, std::sin;
  return atan2(sin(a), cos(a));
}

// a (+) b with c, s = cos, sin of a's heading given: one pose a composed with many (the same
// numbers as compose, without the cosine and sine each time).
inline PlanarPose compose(const PlanarPose& a, double c, double s, const PlanarPose& b) {
  return {a.x() + c * b.x() - s * b.y(), a.y() + s * b.x() + c * b.y(), wrapAngle(a.z() + b.z())};
}

// a (+) b: b expressed in a's frame, brought into a's parent frame.
inline PlanarPose compose(const PlanarPose& a, const PlanarPose& b) { return compose(a, std::cos(a.z()), std::sin(a.z()), b); }

// a^-1, so that compose(a, inverse(a)) is the identity.
inline PlanarPose inverse(const PlanarPose& a) {
  const double c = std::cos(a.z()), s = std::sin(a.z());
  return {-c * a.x() - s * a.y(), s * a.x() - c * a.y(), -a.z()};
}

// a^-1 (+) b: the motion from a to b, in a's frame.
inline PlanarPose between(const PlanarPose& a, const PlanarPose& b) {
  const double c = std::cos(a.z()), s = std::sin(a.z());
  const double dx = b.x() - a.x(), dy = b.y() - a.y();
  return {c * dx + s * dy, -s * dx + c * dy, wrapAngle(b.z() - a.z())};
}

// The 3D pose of a planar one (z = 0, no tilt).
inline Eigen::Isometry3d isometryOf(const PlanarPose& p) {
  Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
  T.linear() = Eigen::AngleAxisd(p.z(), Eigen::Vector3d::UnitZ()).toRotationMatrix();
  T.translation() = Eigen::Vector3d(p.x(), p.y(), 0.0);
  return T;
}

}  // namespace bimloc
