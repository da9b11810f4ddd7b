// Keyframe-plane factor (reference.md, "S-Graphs math"): the wall face moved into the lidar
// frame of the keyframe, compared with the observed plane in the minimal form of the paper's
// Eq. (plane error), (azimuth, elevation, d), whitened by the observation's information.
//
// The keyframe is a planar pose (x, y, yaw) in the map; its roll, pitch and height come from
// odometry (see keyframe.hpp), so the lidar's pose is T_map_lidar = [R(yaw) A, (x, y, z) +
// R(yaw) b] with A = tilt * R_base_lidar and b = tilt * t_base_lidar fixed per keyframe.
// A plane moves with a pose as n_s = R^T n_m, d_s = d_m + n_m · t (reference.md).
#pragma once

#include "wall_geometry.hpp"

#include <Eigen/Core>
#include <ceres/autodiff_cost_function.h>

namespace bimloc::sgraph::detail {

class PlaneFactor {
 public:
  PlaneFactor(const FaceGeometry& face, const Eigen::Matrix3d& A, const Eigen::Vector3d& b, const Eigen::Vector3d& observed,
              const Eigen::Matrix3d& sqrt_information)
      : face_(face), A_(A), b_(b), observed_(observed), sqrt_information_(sqrt_information) {}

  // The face as the lidar at `pose` would see it: (azimuth, elevation, d) in the lidar frame.
  template <typename T>
  static void predict(const FaceGeometry& face, const Eigen::Matrix3d& A, const Eigen::Vector3d& b, const T* pose,
                      const T* node, T out[3]) {
    using std::atan2, std::cos, std::sin, std::sqrt;
    T n[2], d;
    face.plane(node, n, d);
    const T c = cos(pose[2]), s = sin(pose[2]);
    const T nb[2] = {c * n[0] + s * n[1], -s * n[0] + c * n[1]};  // R(yaw)^T n, in the yaw-free base frame
    T ns[3];
    for (int i = 0; i < 3; ++i) ns[i] = A(0, i) * nb[0] + A(1, i) * nb[1];  // A^T: into the lidar frame
    // The lidar's position in the map; its height does not matter, the normal being horizontal.
    const T px = pose[0] + c * b.x() - s * b.y(), py = pose[1] + s * b.x() + c * b.y();
    out[0] = atan2(ns[1], ns[0]);
    out[1] = atan2(ns[2], sqrt(ns[0] * ns[0] + ns[1] * ns[1]));  // = asin(n_z) for a unit normal
    out[2] = d + n[0] * px + n[1] * py;
  }

  template <typename T>
  bool operator()(const T* pose, const T* node, T* residual) const {
    T predicted[3];
    predict(face_, A_, b_, pose, node, predicted);
    const T e[3] = {wrapAngle(T(predicted[0] - observed_[0])), predicted[1] - observed_[1], predicted[2] - observed_[2]};
    for (int i = 0; i < 3; ++i)
      residual[i] = sqrt_information_(i, 0) * e[0] + sqrt_information_(i, 1) * e[1] + sqrt_information_(i, 2) * e[2];
    return true;
  }

  static ceres::CostFunction* create(const FaceGeometry& face, const Eigen::Matrix3d& A, const Eigen::Vector3d& b,
                                     const Eigen::Vector3d& observed, const Eigen::Matrix3d& sqrt_information) {
    return new ceres::AutoDiffCostFunction<PlaneFactor, 3, 3, 3>(new PlaneFactor(face, A, b, observed, sqrt_information));
  }

 private:
  FaceGeometry face_;
  Eigen::Matrix3d A_;
  Eigen::Vector3d b_;
  Eigen::Vector3d observed_;
  Eigen::Matrix3d sqrt_information_;
};

}  // namespace bimloc::sgraph::detail
