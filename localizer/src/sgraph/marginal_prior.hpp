// The window's prior: everything the marginalized keyframes said, as one Gaussian over the
// oldest kept keyframe and the wall nodes they saw, with the correlations between them.
//
// Why dense: a keyframe sees a wall relative to itself. Its plane factor says "the wall is
// 2.31 m from this pose", not "the wall is at y = 4.20"; folded into the wall alone (as
// independent evidence), it would fix the wall wherever the robot then believed it was, and
// the next keyframes would trust that wall as if it were the plan. A robot converged 4 cm off
// would then keep its 4 cm forever, the walls it saw shifted by the same 4 cm (the gauge). The
// Schur complement keeps "wall relative to robot" as it is, so the plan priors of the walls
// (the only absolute information after the filter's start) go on pulling the pair back
// together. This is the marginalization of sliding-window estimators (e.g. OKVIS, VINS-Mono):
// the prior is the linearized cost r(x) = r0 + J (x [-] x0), its Hessian J'J the Schur
// complement, J'r0 its gradient at x0.
#pragma once

#include <Eigen/Core>
#include <ceres/cost_function.h>
#include <vector>

namespace bimloc::sgraph::detail {

struct MarginalPrior {
  // Blocks of three: the keyframe (x, y, yaw) first, then each wall node's (s, alpha, tau).
  std::vector<int> nodes;
  Eigen::VectorXd x0;  // the linearization point
  Eigen::MatrixXd J;   // rows: the directions the prior constrains
  Eigen::VectorXd r0;

  int dimension() const { return 3 + 3 * static_cast<int>(nodes.size()); }
  // The residual at x (the keyframe's heading difference wrapped).
  Eigen::VectorXd residual(const Eigen::VectorXd& x) const;
};

// A prior on the keyframe alone: mean, with independent sigmas (the filter's pose at the start).
MarginalPrior posePrior(const Eigen::Vector3d& mean, const Eigen::Vector3d& sigma);

// The quadratic 1/2 dx'H dx + b'dx (dx = x [-] x0) as a prior; directions of H with an
// eigenvalue below relative_floor * the largest carry nothing and are left out.
MarginalPrior priorFromInformation(const Eigen::MatrixXd& H, const Eigen::VectorXd& b, const Eigen::VectorXd& x0,
                                   std::vector<int> nodes, double relative_floor = 1e-10);

// Gaussian elimination of the variables [begin, begin + size) from 1/2 dx'H dx + b'dx: the
// Schur complement, which is the marginal of the others. H and b shrink by `size`.
void eliminate(Eigen::MatrixXd& H, Eigen::VectorXd& b, int begin, int size);

// The prior as a Ceres factor on the keyframe's pose block and the nodes' blocks, in order.
class MarginalPriorFactor : public ceres::CostFunction {
 public:
  explicit MarginalPriorFactor(const MarginalPrior& prior);
  bool Evaluate(double const* const* parameters, double* residuals, double** jacobians) const override;

 private:
  MarginalPrior prior_;
};

}  // namespace bimloc::sgraph::detail
