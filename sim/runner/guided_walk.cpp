#include "sim/runner/guided_walk.hpp"

#include <bimloc/geometry/planar_pose.hpp>

#include <algorithm>

namespace bimloc::sim {
namespace {

// A goal this close to the one walked to is the same suggestion: no new plan.
constexpr double kSameGoal_m = 0.5;
// Where the goal itself leaves no room for the body: the nearest free spot within this.
constexpr double kGoalSpotSearch_m = 1.0;
// Shorter than this, the remaining run is not worth a plan.
constexpr double kMinPlan_s = 0.5;

double bodyZAtStart(const Simulator& sim) {
  const Pose2& s = sim.start();
  return bodyCentreZ(sim.world(), sim.storey(), {s.x, s.y}, sim.scenario().motion.gait.body_height_m);
}

}  // namespace

GuidedWalk::GuidedWalk(const Simulator& sim)
    : sim_(sim), space_(sim.world(), sim.storey(), sim.scenario().motion.body_radius_m, bodyZAtStart(sim)) {
  pieces_.push_back({0.0, &sim.trajectory()});
}

const GuidedWalk::Piece& GuidedWalk::pieceAt(double t_s) const {
  for (auto it = pieces_.rbegin(); it != pieces_.rend(); ++it)
    if (t_s >= it->t0) return *it;
  return pieces_.front();
}

Eigen::Isometry3d GuidedWalk::T_map_base(double t_s) const {
  const Piece& p = pieceAt(t_s);
  return p.trajectory->T_map_base(t_s - p.t0);
}

double GuidedWalk::handOverTime(double committed_s) const {
  const Piece& p = pieceAt(committed_s);
  return p.t0 + p.trajectory->restAfter(committed_s - p.t0);
}

void GuidedWalk::startPiece(double t0, BaseTrajectory trajectory) {
  while (pieces_.size() > 1 && pieces_.back().t0 >= t0) pieces_.pop_back();  // superseded before it began
  owned_.push_back(std::make_unique<BaseTrajectory>(std::move(trajectory)));
  pieces_.push_back({t0, owned_.back().get()});
}

bool GuidedWalk::walkTo(const Eigen::Vector2d& goal, double committed_s) {
  const double t0 = handOverTime(committed_s);
  const double left = sim_.scenario().duration_s - t0;
  if (left < kMinPlan_s) return false;
  const PlanarPose at = planarPose(T_map_base(t0));
  const Eigen::Vector2d from = at.head<2>();
  const auto spot = space_.freeSpotNear(goal, nullptr, kGoalSpotSearch_m);
  if (!spot) return false;
  std::vector<Eigen::Vector2d> path = space_.path(from, *spot);
  if (path.size() < 2) return false;
  MotionConfig walk = sim_.scenario().motion;
  walk.kind = MotionConfig::Kind::Waypoints;
  walk.waypoints.clear();
  for (std::size_t i = 1; i < path.size(); ++i) walk.waypoints.push_back({path[i], std::nullopt});
  try {
    startPiece(t0, BaseTrajectory::plan(sim_.world(), sim_.storey(), {at.x(), at.y(), at.z()}, walk, left, sim_.scenario().seed));
  } catch (const std::exception&) {  // a path the final sweep refuses (MotionError): out of reach
    return false;
  }
  return true;
}

void GuidedWalk::tour(double committed_s) {
  touring_ = true;
  goal_.reset();
  const double t0 = handOverTime(committed_s);
  const double left = sim_.scenario().duration_s - t0;
  if (left < kMinPlan_s) return;
  const PlanarPose at = planarPose(T_map_base(t0));
  MotionConfig script = sim_.scenario().motion;
  script.disambiguate = false;
  try {
    startPiece(t0, BaseTrajectory::plan(sim_.world(), sim_.storey(), {at.x(), at.y(), at.z()}, script, left, sim_.scenario().seed));
  } catch (const std::exception&) {
    MotionConfig stand = script;
    stand.kind = MotionConfig::Kind::Stand;
    startPiece(t0, BaseTrajectory::plan(sim_.world(), sim_.storey(), {at.x(), at.y(), at.z()}, stand, left, sim_.scenario().seed));
  }
}

void GuidedWalk::follow(LocalizationState state, const std::optional<guide::LookGoal>& suggested,
                        const Eigen::Isometry3d& T_odom_base, const Eigen::Isometry3d& truth, double committed_s) {
  if (converged_) return;
  const Piece& now = pieceAt(committed_s);
  const bool arrived = committed_s - now.t0 >= now.trajectory->script_duration_s();
  if (state == LocalizationState::Converged || state == LocalizationState::Tracking) {
    // Decided: on with the script from where the base stops next. A tour already under way
    // (no goal was ever taken) just goes on.
    converged_ = true;
    if (!touring_) tour(committed_s);
    return;
  }
  if (suggested) {
    // world <- odom of the run, from the truth now: the goal where the robot would walk it.
    const PlanarPose T_world_odom = compose(planarPose(truth), inverse(planarPose(T_odom_base)));
    const Eigen::Vector2d goal = compose(T_world_odom, suggested->T_odom_goal).head<2>();
    const bool same = goal_ && (goal - *goal_).norm() < kSameGoal_m;
    const bool refused = refused_ && (goal - *refused_).norm() < kSameGoal_m;
    if (same && !touring_ && arrived) {
      // Stopped short of it (the spot nearest it where the body fits): the script until the
      // localizer suggests another.
      refused_ = goal;
      tour(committed_s);
      return;
    }
    if (same || refused) return;
    if (walkTo(goal, committed_s)) {
      goal_ = goal, touring_ = false, ++goals_taken_;
      refused_.reset();
    } else {
      refused_ = goal;
    }
    return;
  }
  // No goal: once the goal walked to is reached (the piece has ended), the script again.
  if (!touring_ && arrived) tour(committed_s);
}

}  // namespace bimloc::sim
