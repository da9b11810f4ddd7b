// Scoring a localization run against the ground truth, the same way for a simulated run
// (`bimloc run`) and a recorded dataset (`bimloc localize`): convergence time, room found,
// errors, ATE (RMSE of position after convergence, in the plan's frame, no alignment) and
// false convergence (declared converged while more than 0.5 m or 10 degrees off, or on
// another storey than the truth's, at any time).
#pragma once

#include "sim/runner/run_scenario.hpp"

namespace bimloc::sim {

class RunScore {
 public:
  // `storey`: the true storey (an index into building.storeys).
  RunScore(const bim::Building& building, std::size_t storey) : building_(building), storey_(storey) {}

  // After each localizer update at time t, with the true pose at that time. Returns true on
  // the update where the localizer declared convergence.
  bool add(double t, const pf::StoreyBank& localizer, const Eigen::Isometry3d& truth);
  // Fills the result's scores from the last update.
  void finish(const pf::StoreyBank& localizer, ScenarioResult& result) const;

 private:
  const bim::Building& building_;
  std::size_t storey_;
  Eigen::Isometry3d truth_ = Eigen::Isometry3d::Identity();
  Eigen::Isometry3d estimate_ = Eigen::Isometry3d::Identity();
  bool converged_ = false, false_convergence_ = false;
  double convergence_time_ = 0, sum_sq_ = 0;
  int after_ = 0;
  std::string found_room_, true_room_, found_storey_;
};

double yawErrorDeg(const Eigen::Isometry3d& a, const Eigen::Isometry3d& b);

}  // namespace bimloc::sim
