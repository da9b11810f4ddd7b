// Odometry factor between consecutive keyframes (the robot-tracking layer): the planar
// increment the odometry measured, in the frame of the first keyframe (paper Eq. of u_R),
// against the increment of the two estimated poses. Its sigmas grow with the motion.
#pragma once

#include "wall_geometry.hpp"

#include <Eigen/Core>
#include <ceres/autodiff_cost_function.h>

namespace bimloc::sgraph::detail {

class OdometryFactor {
 public:
  // delta = (dx, dy, dyaw) of keyframe j in keyframe i's frame; sigma per component.
  OdometryFactor(const Eigen::Vector3d& delta, const Eigen::Vector3d& sigma) : delta_(delta), inverse_sigma_(sigma.cwiseInverse()) {}

  template <typename T>
  bool operator()(const T* a, const T* b, T* residual) const {
    using std::cos, std::sin;
    const T c = cos(a[2]), s = sin(a[2]);
    const T dx = b[0] - a[0], dy = b[1] - a[1];
    residual[0] = (c * dx + s * dy - delta_.x()) * inverse_sigma_.x();
    residual[1] = (-s * dx + c * dy - delta_.y()) * inverse_sigma_.y();
    residual[2] = wrapAngle(T(b[2] - a[2] - delta_.z())) * inverse_sigma_.z();
    return true;
  }

  static ceres::CostFunction* create(const Eigen::Vector3d& delta, const Eigen::Vector3d& sigma) {
    return new ceres::AutoDiffCostFunction<OdometryFactor, 3, 3, 3>(new OdometryFactor(delta, sigma));
  }

 private:
  Eigen::Vector3d delta_;
  Eigen::Vector3d inverse_sigma_;
};

}  // namespace bimloc::sgraph::detail
