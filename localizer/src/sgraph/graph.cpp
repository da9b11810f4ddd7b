#include "graph.hpp"

#include <bimloc/geometry/planar_pose.hpp>

#include <cmath>

namespace bimloc::sgraph::detail {

Eigen::Isometry3d Keyframe::T_map_base() const {
  Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
  T.linear() = Eigen::AngleAxisd(pose[2], Eigen::Vector3d::UnitZ()).toRotationMatrix() * tilt;
  T.translation() = Eigen::Vector3d(pose[0], pose[1], z_map);
  return T;
}

Eigen::Vector2d WallNode::normal(int k) const {
  double n[2], d;
  face[k].plane(params.data(), n, d);
  return {n[0], n[1]};
}

double WallNode::d(int k) const {
  double n[2], d;
  face[k].plane(params.data(), n, d);
  return d;
}

bim::WallAxis WallNode::axis(int k) const {
  const Eigen::Vector2d n = normal(k);
  return std::abs(n.x()) >= std::abs(n.y()) ? bim::WallAxis::X : bim::WallAxis::Y;
}

double WallNode::along(int k, const Eigen::Vector2d& p) const {
  const Eigen::Vector2d u = end[k] - start[k];
  const double length = u.norm();
  return length > 0 ? (p - start[k]).dot(u / length) : 0.0;
}

}  // namespace bimloc::sgraph::detail
