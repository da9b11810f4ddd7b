// Scoring a localization run against the ground truth, the same way for a simulated run
// (`bimloc run`) and a recorded dataset (`bimloc localize`): convergence time, room found,
// errors, ATE (RMSE of position after convergence, in the plan's frame, no alignment) and
// false convergence (declared converged, or tracking, while more than 0.5 m or 10 degrees
// off, or on another storey than the truth's, at any time; a localizer that says it is lost
// is not wrong with confidence), RPE and losses of track. The true storey follows the base
// (issue 31): the storey whose floor its z stands on, from the start storey's floor and the
// truth's height change; a change of storey is followed when the localizer is on the new
// storey within kFollowWindowS of the base leaving the flight (the simulator says when; a
// recording: its height on the new floor), and until then (and while the base is on the
// stairs) the old storey is not a false convergence.
#pragma once

#include "sim/runner/run_scenario.hpp"

#include <utility>
#include <vector>

namespace bimloc::sim {

class RunScore {
 public:
  // `storey`: the true storey at the start (an index into building.storeys).
  RunScore(const bim::Building& building, std::size_t storey) : building_(building), storey_(storey), start_storey_(storey) {}
  static constexpr double kFollowWindowS = 5.0;

  // After each localizer step at time t, with the true pose at that time. Returns true on
  // the step where the localizer declared convergence.
  // `on_flight`: whether the base is on a flight of stairs then, when the source knows (the
  // simulator does): the follow lag is timed from the base leaving the flight. Without it
  // (a recording), from the base's height reaching the new floor (floorStorey).
  bool add(double t, const LocalizationResult& step, const Eigen::Isometry3d& truth, std::optional<bool> on_flight = std::nullopt);
  bool converged() const { return converged_; }
  // Whether the ATE counts the step: converged (or tracking) on a storey, and not lost.
  static bool scored(const LocalizationResult& step) {
    return step.state != LocalizationState::Searching && step.state != LocalizationState::Lost && step.storey.has_value();
  }
  // Fills the result's scores from the last step.
  void finish(ScenarioResult& result) const;
  std::size_t trueStorey() const { return storey_; }  // at the last step
  bool onStairs() const { return on_stairs_; }         // ... between floors

  // The storey whose floor a base at height z stands on, given the start storey and the
  // base's height there (base_link above its floor); none between floors (on the stairs).
  static std::optional<std::size_t> floorStorey(const bim::Building& building, std::size_t start_storey, double start_z, double z);

 private:
  void followStorey(double t, const LocalizationResult& step, const Eigen::Isometry3d& truth, std::optional<bool> on_flight);

  const bim::Building& building_;
  std::size_t storey_, start_storey_;
  std::optional<double> start_z_;
  bool on_stairs_ = false;
  std::optional<double> changed_at_;  // the base's height reached storey_'s floor then (the last change)
  std::optional<double> left_at_;     // ... and it left the flight then: the follow lag's clock
  double last_t_ = 0;                 // the last step's time
  bool change_followed_ = true;
  int storey_changes_ = 0, storey_changes_followed_ = 0, storey_changes_searching_ = 0;
  std::vector<double> follow_lags_s_;
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
