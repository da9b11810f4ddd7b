// The base steered while the run goes on (motion.disambiguate, issue 28 §4): it walks where the
// localizer suggests looking (LocalizationResult::goal, in the odom frame, brought into the
// world with the run's truth: world <- odom), plans again when the suggestion changes (places
// ruled out), and follows the scenario's script (a tour) when there is no goal and after
// convergence. A new plan takes over at the next moment the base is at rest (the end of the
// turn or straight move under way: every move is rest to rest), and never before the poses
// already handed to the lidar: the walk is causal, step by step.
#pragma once

#include "sim/base/base_trajectory.hpp"
#include "sim/base/free_space.hpp"
#include "sim/simulation/simulator.hpp"

#include <bimloc/localizer.hpp>

#include <memory>
#include <optional>
#include <vector>

namespace bimloc::sim {

class GuidedWalk {
 public:
  // Starts on the simulator's own plan (the script from the start), until told otherwise.
  explicit GuidedWalk(const Simulator& sim);

  // Ground truth map <- base at time t.
  Eigen::Isometry3d T_map_base(double t_s) const;
  // After the localizer's step at `t_s` (odometry T_odom_base, truth `truth`): follow its goal,
  // or the script. Poses up to `committed_s` have been used (the lidar's turn so far).
  void follow(LocalizationState state, const std::optional<guide::LookGoal>& goal, const Eigen::Isometry3d& T_odom_base,
              const Eigen::Isometry3d& truth, double committed_s);

  // The goal being walked to (world frame), if any; how many goals were taken up.
  const std::optional<Eigen::Vector2d>& goal() const { return goal_; }
  int goalsTaken() const { return goals_taken_; }

 private:
  struct Piece {
    double t0 = 0;
    const BaseTrajectory* trajectory = nullptr;
  };
  // The piece under way at t, and the moment (>= committed) a new one can start.
  const Piece& pieceAt(double t_s) const;
  double handOverTime(double committed_s) const;
  void startPiece(double t0, BaseTrajectory trajectory);
  bool walkTo(const Eigen::Vector2d& goal, double committed_s);  // false: unreachable from here
  void tour(double committed_s);

  const Simulator& sim_;
  FreeSpace space_;
  std::vector<Piece> pieces_;
  std::vector<std::unique_ptr<BaseTrajectory>> owned_;
  std::optional<Eigen::Vector2d> goal_;     // the goal walked to (world)
  std::optional<Eigen::Vector2d> refused_;  // the last goal found out of reach
  bool touring_ = true;                     // following the script (no goal, or converged)
  bool converged_ = false;
  int goals_taken_ = 0;
};

}  // namespace bimloc::sim
