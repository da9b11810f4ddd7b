#include "sim/runner/evaluation.hpp"

#include "sim/base/room_lookup.hpp"

#include <bimloc/geometry/planar_pose.hpp>

#include <cmath>

namespace bimloc::sim {
namespace {

constexpr double kFalsePositionM = 0.5;  // declared converged while farther off than this ...
constexpr double kFalseYawDeg = 10.0;    // ... or turned more than this: a false convergence

// The room the true pose is in, by name.
std::string trueRoom(const bim::Storey& storey, const Eigen::Isometry3d& truth) {
  const bim::Room* room = roomAt(storey, truth.translation().head<2>());
  return room ? room->name : std::string("(outside)");
}

}  // namespace

double yawErrorDeg(const Eigen::Isometry3d& a, const Eigen::Isometry3d& b) {
  return std::abs(wrapAngle(yawOf(a.linear()) - yawOf(b.linear()))) * 180.0 / M_PI;
}

std::optional<std::size_t> RunScore::floorStorey(const bim::Building& building, std::size_t start_storey, double start_z, double z) {
  constexpr double kOnFloorM = 0.3;  // a riser is 0.15-0.2 m: within this, the base stands on the floor
  const double start_floor = building.storeys.at(start_storey).elevation_m;
  std::optional<std::size_t> best;
  double best_d = kOnFloorM;
  for (std::size_t s = 0; s < building.storeys.size(); ++s) {
    const double d = std::abs(z - start_z - (building.storeys[s].elevation_m - start_floor));
    if (d < best_d || (s == start_storey && d <= best_d)) best_d = d, best = s;
  }
  return best;
}

// The true storey by the base's height; the changes and whether the localizer followed them.
void RunScore::followStorey(double t, const LocalizationResult& step, const Eigen::Isometry3d& truth, std::optional<bool> on_flight) {
  if (!start_z_) start_z_ = truth.translation().z();
  // On a flight the base is on no storey, whatever its height: a flight passes the heights of
  // other storeys of the plan (Jesse.1: its T.O. level 0 floor, 0.36 m under level 0, half way up
  // the flight from Level -1), and the base on its last risers has not arrived yet.
  const std::optional<std::size_t> on =
      on_flight.value_or(false) ? std::nullopt : floorStorey(building_, start_storey_, *start_z_, truth.translation().z());
  on_stairs_ = !on;
  if (on && *on != storey_) {
    storey_ = *on;
    changed_at_ = t;
    left_at_.reset();
    // Before the first convergence the localizer tracks no storey: there is nothing to follow
    // (its search is scored by the convergence, which must then be on the storey the base is
    // on). Such a change is counted apart, not as one followed or missed.
    change_followed_ = !converged_;
    ++(converged_ ? storey_changes_ : storey_changes_searching_);
  }
  // The clock starts when the base steps off the flight (issue 31: "from leaving a flight"); a
  // recording's, when its height is on the new floor (within a riser or two of it).
  if (changed_at_ && !left_at_ && !on_flight.value_or(false)) left_at_ = t;
  if (!change_followed_ && changed_at_ && (!left_at_ || t <= *left_at_ + kFollowWindowS) && step.storey == storey_) {
    change_followed_ = true;
    ++storey_changes_followed_;
    follow_lags_s_.push_back(left_at_ ? t - *left_at_ : 0.0);  // 0: on the new storey before the base left the flight
  }
}

bool RunScore::add(double t, const LocalizationResult& step, const Eigen::Isometry3d& truth, std::optional<bool> on_flight) {
  followStorey(t, step, truth, on_flight);
  last_t_ = t;
  truth_ = truth;
  estimate_ = step.T_map_base;
  losses_ = step.losses;
  if (step.state == LocalizationState::Searching || !step.storey) return false;
  const bool first = !converged_;
  if (first) {
    converged_ = true;
    convergence_time_ = t;
    found_room_ = step.room < 0 ? std::string("(outside)") : step.room_name;
    found_storey_ = building_.storeyLabel(*step.storey);
    true_room_ = trueRoom(building_.storeys.at(storey_), truth);
  }
  if (!scored(step)) return first;  // lost: it says it does not know
  // Right place, wrong storey is a false convergence too: the plan's x, y repeat on every storey.
  const double error = (estimate_.translation() - truth.translation()).head<2>().norm();
  // The storey it left counts as wrong once the localizer had its window to follow.
  const bool following = changed_at_ && (!left_at_ || t <= *left_at_ + kFollowWindowS);
  const bool wrong_storey = *step.storey != storey_ && !on_stairs_ && !following;
  if (error > kFalsePositionM || yawErrorDeg(estimate_, truth) > kFalseYawDeg || wrong_storey) false_convergence_ = true;
  sum_sq_ += error * error;
  ++after_;
  track_.emplace_back(planarPose(truth), planarPose(estimate_));
  return first;
}

// Relative pose error per metre: over each stretch of 1 m of true path, the translation the
// estimate made against the one the truth made, both in the stretch's start frame.
static std::optional<double> relativeErrorPerMetre(const std::vector<std::pair<Eigen::Vector3d, Eigen::Vector3d>>& track) {
  const auto relative = [](const Eigen::Vector3d& a, const Eigen::Vector3d& b) {
    return Eigen::Rotation2Dd(-a.z()) * Eigen::Vector2d(b.head<2>() - a.head<2>());
  };
  double sum_sq = 0;
  int n = 0;
  std::size_t j = 0;
  double walked = 0;  // true path length from i to j
  for (std::size_t i = 0; i < track.size(); ++i) {
    if (i > 0) walked -= (track[i].first.head<2>() - track[i - 1].first.head<2>()).norm();
    if (j < i) j = i, walked = 0;
    while (walked < 1.0 && j + 1 < track.size()) {
      walked += (track[j + 1].first.head<2>() - track[j].first.head<2>()).norm();
      ++j;
    }
    if (walked < 1.0) break;
    const Eigen::Vector2d e = relative(track[i].second, track[j].second) - relative(track[i].first, track[j].first);
    sum_sq += e.squaredNorm() / (walked * walked);
    ++n;
  }
  if (n == 0) return std::nullopt;
  return std::sqrt(sum_sq / n);
}

void RunScore::finish(ScenarioResult& r) const {
  r.converged = converged_;
  r.false_convergence = false_convergence_;
  r.losses = losses_;
  // A change the run ended on before the localizer had its window (the tour's last flight, a
  // few seconds before the end) and not followed yet is not judged: it is no change missed.
  const bool cut_short = !change_followed_ && left_at_ && last_t_ < *left_at_ + kFollowWindowS;
  r.storey_changes = storey_changes_ - (cut_short ? 1 : 0);
  r.storey_changes_followed = storey_changes_followed_;
  r.storey_changes_searching = storey_changes_searching_;
  r.storey_follow_lags_s = follow_lags_s_;
  if (converged_) {
    r.convergence_time_s = convergence_time_;
    r.found_room = found_room_;
    r.true_room = true_room_;
    r.found_storey = found_storey_;
  } else {
    r.true_room = trueRoom(building_.storeys.at(storey_), truth_);
  }
  r.position_error_m = (estimate_.translation() - truth_.translation()).head<2>().norm();
  r.yaw_error_deg = yawErrorDeg(estimate_, truth_);
  if (after_ > 0) r.ate_m = std::sqrt(sum_sq_ / after_);
  r.rpe_m_per_m = relativeErrorPerMetre(track_);
}

}  // namespace bimloc::sim
