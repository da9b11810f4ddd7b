// Scoring a localization run against the ground truth, the same way for a simulated run
// (`bimloc run`) and a recorded dataset (`bimloc localize`): convergence time, room found,
// errors, ATE (RMSE of position after convergence, in the plan's frame, no alignment) and
// false convergence (declared converged, or tracking, while more than 0.5 m or 10 degrees
// off, or on another storey than the truth's, at any time; a localizer that says it is lost
// is not wrong with confidence), RPE and losses of track.
#pragma once

#include "sim/runner/run_scenario.hpp"

#include <utility>
#include <vector>

namespace bimloc::sim {

class RunScore {
 public:
  // `storey`: the true storey (an index into building.storeys).
  RunScore(const bim::Building& building, std::size_t storey) : building_(building), storey_(storey) {}

  // After each localizer step at time t, with the true pose at that time. Returns true on
  // the step where the localizer declared convergence.
  bool add(double t, const LocalizationResult& step, const Eigen::Isometry3d& truth);
  bool converged() const { return converged_; }
  // Whether the ATE counts the step: converged (or tracking) on a storey, and not lost.
  static bool scored(const LocalizationResult& step) {
    return step.state != LocalizationState::Searching && step.state != LocalizationState::Lost && step.storey.has_value();
  }
  // Fills the result's scores from the last step.
  void finish(ScenarioResult& result) const;

 private:
  const bim::Building& building_;
  std::size_t storey_;
  Eigen::Isometry3d truth_ = Eigen::Isometry3d::Identity();
  Eigen::Isometry3d estimate_ = Eigen::Isometry3d::Identity();
  bool converged_ = false, false_convergence_ = false;
  double convergence_time_ = 0, sum_sq_ = 0;
  int after_ = 0, losses_ = 0;
  // After convergence, while not lost: (truth, estimate) map x, y, yaw, for the RPE.
  std::vector<std::pair<Eigen::Vector3d, Eigen::Vector3d>> track_;
  std::string found_room_, true_room_, found_storey_;
};

double yawErrorDeg(const Eigen::Isometry3d& a, const Eigen::Isometry3d& b);

}  // namespace bimloc::sim
