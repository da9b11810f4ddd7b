#include "sim/runner/evaluation.hpp"

#include "sim/base/room_lookup.hpp"

#include <bimloc/geometry/planar_pose.hpp>

#include <cmath>

namespace bimloc::sim {
namespace {

constexpr double kFalsePositionM = 0.5;  // declared converged while farther off than this ...
constexpr double kFalseYawDeg = 10.0;    // ... or turned more than this: a false convergence

std::string roomName(const bim::Storey& storey, int index) {
  return index < 0 ? std::string("(outside)") : storey.rooms[static_cast<std::size_t>(index)].name;
}

// The room the true pose is in, by name.
std::string trueRoom(const bim::Storey& storey, const Eigen::Isometry3d& truth) {
  const bim::Room* room = roomAt(storey, truth.translation().head<2>());
  return room ? room->name : std::string("(outside)");
}

}  // namespace

double yawErrorDeg(const Eigen::Isometry3d& a, const Eigen::Isometry3d& b) {
  const double d = yawOf(a.linear()) - yawOf(b.linear());
  return std::abs(std::atan2(std::sin(d), std::cos(d))) * 180.0 / M_PI;
}

bool RunScore::add(double t, const pf::StoreyBank& localizer, const Eigen::Isometry3d& truth) {
  truth_ = truth;
  estimate_ = localizer.T_map_base();
  if (!localizer.converged()) return false;
  const bool first = !converged_;
  const bim::Storey& found = building_.storeys.at(*localizer.storey());
  if (first) {
    converged_ = true;
    convergence_time_ = t;
    found_room_ = roomName(found, localizer.estimateRoom());
    found_storey_ = found.name;
    true_room_ = trueRoom(building_.storeys.at(storey_), truth);
  }
  // Right place, wrong storey is a false convergence too: the plan's x, y repeat on every storey.
  const double error = (estimate_.translation() - truth.translation()).head<2>().norm();
  if (error > kFalsePositionM || yawErrorDeg(estimate_, truth) > kFalseYawDeg || *localizer.storey() != storey_)
    false_convergence_ = true;
  sum_sq_ += error * error;
  ++after_;
  return first;
}

void RunScore::finish(const pf::StoreyBank& localizer, ScenarioResult& r) const {
  const Eigen::Isometry3d estimate = localizer.T_map_base();
  r.converged = converged_;
  r.false_convergence = false_convergence_;
  if (converged_) {
    r.convergence_time_s = convergence_time_;
    r.found_room = found_room_;
    r.true_room = true_room_;
    r.found_storey = found_storey_;
  } else {
    r.true_room = trueRoom(building_.storeys.at(storey_), truth_);
  }
  r.position_error_m = (estimate.translation() - truth_.translation()).head<2>().norm();
  r.yaw_error_deg = yawErrorDeg(estimate, truth_);
  if (after_ > 0) r.ate_m = std::sqrt(sum_sq_ / after_);
}

}  // namespace bimloc::sim
