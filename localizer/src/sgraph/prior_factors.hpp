// Unary factors: what the graph knows of a node before (or besides) the window's scans.
//   GaussianPrior  the room nodes' plan centres.
//   WallPrior      a plan wall at its plan position, to its as-built tolerance (s, alpha).
//   ThicknessPrior the plan's thickness (tau = 0).
// (What marginalized keyframes said is the MarginalPrior, marginal_prior.hpp.)
#pragma once

#include "wall_geometry.hpp"

#include <Eigen/Core>
#include <ceres/autodiff_cost_function.h>

namespace bimloc::sgraph::detail {

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
