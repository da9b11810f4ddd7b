// The sliding-window optimization: the Ceres problem of the window's keyframes, the wall
// nodes they observed, the rooms of those walls, and all the factors between them, solved
// with Levenberg-Marquardt; and the factors' construction, shared with the marginalization.
#pragma once

#include "graph.hpp"

#include <ceres/cost_function.h>
#include <optional>
#include <string>

namespace bimloc::sgraph::detail {

struct SolveReport {
  int iterations = 0;
  double initial_cost = 0, final_cost = 0;
  double time_s = 0;
  bool usable = true;  // false: the solver failed or diverged; the estimate was left as it was
  std::string message;
  // Marginal covariance of the newest keyframe's (x, y, yaw) at the solution (Ceres'
  // Covariance, robust kernels applied); unset when the Jacobian is rank deficient.
  std::optional<Eigen::Matrix3d> newest_covariance;
};

SolveReport optimizeWindow(Graph& g, const SGraphConfig& config);

// Sigmas of the odometry link a -> b (config noise model; the jump sigmas across a jump).
Eigen::Vector3d odometrySigma(const Keyframe& a, const Keyframe& b, const SGraphConfig& config);
ceres::CostFunction* odometryCost(const Keyframe& a, const Keyframe& b, const SGraphConfig& config);
ceres::CostFunction* planeCost(const Graph& g, const Keyframe& kf, const PlaneMeasurement& m);

// Squared Mahalanobis residual of each of the keyframe's plane measurements at the current
// estimate (no robust kernel).
std::vector<double> planeResiduals2(const Graph& g, const Keyframe& kf);

}  // namespace bimloc::sgraph::detail
