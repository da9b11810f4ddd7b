// Unary factors: what the graph knows of a node before (or besides) the window's scans.
//   PosePrior      the oldest keyframe of the window: what the marginalized keyframes said
//                  about it (marginalization.cpp), or the particle filter's pose at the start.
//   GaussianPrior  a node's evidence from marginalized keyframes (canonical form -> mean and
//                  square-root information), and the room nodes' plan centres.
//   WallPrior      a plan wall at its plan position, to its as-built tolerance (s, alpha).
//   ThicknessPrior the plan's thickness (tau = 0).
#pragma once

#include "wall_geometry.hpp"

#include <Eigen/Core>
#include <ceres/autodiff_cost_function.h>

namespace bimloc::sgraph::detail {

class PosePrior {
 public:
  PosePrior(const Eigen::Vector3d& mean, const Eigen::Matrix3d& sqrt_information) : mean_(mean), L_(sqrt_information) {}

  template <typename T>
  bool operator()(const T* pose, T* residual) const {
    const T e[3] = {pose[0] - mean_.x(), pose[1] - mean_.y(), wrapAngle(T(pose[2] - mean_.z()))};
    for (int i = 0; i < 3; ++i) residual[i] = L_(i, 0) * e[0] + L_(i, 1) * e[1] + L_(i, 2) * e[2];
    return true;
  }

  static ceres::CostFunction* create(const Eigen::Vector3d& mean, const Eigen::Matrix3d& sqrt_information) {
    return new ceres::AutoDiffCostFunction<PosePrior, 3, 3>(new PosePrior(mean, sqrt_information));
  }

 private:
  Eigen::Vector3d mean_;
  Eigen::Matrix3d L_;
};

template <int N>
class GaussianPrior {
 public:
  using Vector = Eigen::Matrix<double, N, 1>;
  using Matrix = Eigen::Matrix<double, N, N>;
  GaussianPrior(const Vector& mean, const Matrix& sqrt_information) : mean_(mean), L_(sqrt_information) {}

  template <typename T>
  bool operator()(const T* x, T* residual) const {
    for (int i = 0; i < N; ++i) {
      residual[i] = T(0);
      for (int j = 0; j < N; ++j) residual[i] += L_(i, j) * (x[j] - mean_[j]);
    }
    return true;
  }

  static ceres::CostFunction* create(const Vector& mean, const Matrix& sqrt_information) {
    return new ceres::AutoDiffCostFunction<GaussianPrior, N, N>(new GaussianPrior(mean, sqrt_information));
  }

 private:
  Vector mean_;
  Matrix L_;
};

class WallPrior {
 public:
  WallPrior(double sigma_m, double sigma_rad) : inverse_sigma_m_(1.0 / sigma_m), inverse_sigma_rad_(1.0 / sigma_rad) {}

  template <typename T>
  bool operator()(const T* node, T* residual) const {
    residual[0] = node[0] * inverse_sigma_m_;
    residual[1] = node[1] * inverse_sigma_rad_;
    return true;
  }

  static ceres::CostFunction* create(double sigma_m, double sigma_rad) {
    return new ceres::AutoDiffCostFunction<WallPrior, 2, 3>(new WallPrior(sigma_m, sigma_rad));
  }

 private:
  double inverse_sigma_m_, inverse_sigma_rad_;
};

class ThicknessPrior {
 public:
  explicit ThicknessPrior(double sigma_m) : inverse_sigma_m_(1.0 / sigma_m) {}

  template <typename T>
  bool operator()(const T* node, T* residual) const {
    residual[0] = node[2] * inverse_sigma_m_;
    return true;
  }

  static ceres::CostFunction* create(double sigma_m) {
    return new ceres::AutoDiffCostFunction<ThicknessPrior, 1, 3>(new ThicknessPrior(sigma_m));
  }

 private:
  double inverse_sigma_m_;
};

}  // namespace bimloc::sgraph::detail
