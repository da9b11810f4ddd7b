#include "sim/base/motion_profile.hpp"

#include <bimloc/geometry/planar_pose.hpp>
#include <algorithm>
#include <cmath>

namespace bimloc::sim {
namespace {

// Floor samples along a move: fine enough for a ramp, coarse enough to build fast.
constexpr double kFloorStep_m = 0.25;
constexpr double kMinTurn_rad = 1e-6;
constexpr double kMinMove_m = 1e-6;

using bimloc::wrapAngle;

}  // namespace

RestToRest RestToRest::plan(double length, double v_max, double a_max) {
  RestToRest p;
  p.length = length;
  p.accel = a_max;
  if (length <= 0.0) return p;
  if (length >= v_max * v_max / a_max) {  // reaches v_max: trapezoid
    p.v_peak = v_max;
    p.t_ramp = v_max / a_max;
    p.t_cruise = (length - v_max * v_max / a_max) / v_max;
  } else {  // triangle
    p.v_peak = std::sqrt(length * a_max);
    p.t_ramp = p.v_peak / a_max;
  }
  return p;
}

double RestToRest::position(double t) const {
  if (t <= 0.0) return 0.0;
  if (t >= duration()) return length;
  if (t < t_ramp) return 0.5 * accel * t * t;
  const double ramp = 0.5 * v_peak * t_ramp;
  if (t < t_ramp + t_cruise) return ramp + v_peak * (t - t_ramp);
  const double left = duration() - t;
  return length - 0.5 * accel * left * left;
}

double RestToRest::speed(double t) const {
  if (t <= 0.0 || t >= duration()) return 0.0;
  if (t < t_ramp) return accel * t;
  if (t < t_ramp + t_cruise) return v_peak;
  return accel * (duration() - t);
}

Timeline::Timeline(const Eigen::Vector2d& start, double yaw, const MotionLimits& limits,
                   std::function<double(const Eigen::Vector2d&)> floor_z, int storey)
    : limits_(limits), floor_z_(std::move(floor_z)), position_(start), yaw_(yaw), storey_(storey) {
  floor_here_ = floor_z_(start);
}

void Timeline::turnTo(double yaw) {
  const double delta = wrapAngle(yaw - yaw_);
  if (std::abs(delta) < kMinTurn_rad) return;
  Phase p;
  p.t0 = end_s();
  p.from = position_;
  p.yaw0 = yaw_;
  p.turn_sign = delta > 0.0 ? 1.0 : -1.0;
  p.distance0 = distance_;
  p.profile = RestToRest::plan(std::abs(delta), limits_.max_turn_rate_rps, limits_.max_turn_accel_rps2);
  p.t1 = p.t0 + p.profile.duration();
  p.floor_z = {floor_here_};
  p.storey = storey_;
  phases_.push_back(std::move(p));
  yaw_ += delta;
}

void Timeline::addMove(const Eigen::Vector2d& target, std::vector<double> floor_z, double max_speed_mps, bool stairs) {
  const Eigen::Vector2d d = target - position_;
  const double length = d.norm();
  Phase p;
  p.move = true;
  p.t0 = end_s();
  p.from = position_;
  p.dir = d / length;
  p.yaw0 = yaw_;
  p.distance0 = distance_;
  p.profile = RestToRest::plan(length, std::min(max_speed_mps, limits_.max_speed_mps), limits_.max_accel_mps2);
  p.t1 = p.t0 + p.profile.duration();
  p.floor_z = std::move(floor_z);
  p.slope_rad = stairs ? std::atan2(p.floor_z.back() - p.floor_z.front(), length) : 0.0;
  p.storey = storey_;
  p.stairs = stairs;
  phases_.push_back(std::move(p));
  position_ = target;
  distance_ += length;
  floor_here_ = phases_.back().floor_z.back();
}

void Timeline::moveTo(const Eigen::Vector2d& target) {
  const Eigen::Vector2d d = target - position_;
  const double length = d.norm();
  if (length < kMinMove_m) return;
  turnTo(std::atan2(d.y(), d.x()));
  const int samples = std::max(1, static_cast<int>(std::ceil(length / kFloorStep_m)));
  std::vector<double> floor_z;
  for (int i = 0; i <= samples; ++i) floor_z.push_back(floor_z_(position_ + d * (double(i) / samples)));
  addMove(target, std::move(floor_z), limits_.max_speed_mps, false);
}

void Timeline::moveFlatTo(const Eigen::Vector2d& target, double z) {
  const Eigen::Vector2d d = target - position_;
  if (d.norm() < kMinMove_m) {
    floor_here_ = z;
    return;
  }
  turnTo(std::atan2(d.y(), d.x()));
  addMove(target, {floor_here_, z}, limits_.max_speed_mps, false);
}

void Timeline::climbTo(const Eigen::Vector2d& target, double z_end, double max_speed_mps, int storey_after) {
  const Eigen::Vector2d d = target - position_;
  if (d.norm() >= kMinMove_m) {
    turnTo(std::atan2(d.y(), d.x()));
    addMove(target, {floor_here_, z_end}, max_speed_mps, true);
  }
  floor_here_ = z_end;
  storey_ = storey_after;
}

const Timeline::Phase* Timeline::find(double t_s) const {
  if (phases_.empty() || t_s < phases_.front().t0 || t_s >= phases_.back().t1) return nullptr;
  const auto it = std::upper_bound(phases_.begin(), phases_.end(), t_s,
                                   [](double t, const Phase& p) { return t < p.t0; });
  return &*std::prev(it);
}

PlanarState Timeline::at(double t_s) const {
  PlanarState s;
  const Phase* p = find(t_s);
  if (!p) {  // before the first phase or after the last: standing
    const bool after = !phases_.empty() && t_s >= phases_.back().t1;
    s.xy = after ? position_ : (phases_.empty() ? position_ : phases_.front().from);
    s.yaw = after ? yaw_ : (phases_.empty() ? yaw_ : phases_.front().yaw0);
    s.distance = after ? distance_ : 0.0;
    s.floor_z = after ? floor_here_ : (phases_.empty() ? floor_here_ : phases_.front().floor_z.front());
    s.storey = after || phases_.empty() ? storey_ : phases_.front().storey;
    return s;
  }
  const double tau = t_s - p->t0;
  const double q = p->profile.position(tau);
  s.storey = p->storey;
  if (!p->move) {
    s.xy = p->from;
    s.yaw = p->yaw0 + p->turn_sign * q;
    s.turn_rate = p->turn_sign * p->profile.speed(tau);
    s.distance = p->distance0;
    s.floor_z = p->floor_z.front();
    return s;
  }
  s.xy = p->from + q * p->dir;
  s.yaw = p->yaw0;
  s.speed = p->profile.speed(tau);
  s.distance = p->distance0 + q;
  s.slope_rad = p->slope_rad;
  s.on_stairs = p->stairs;
  // Linear between the floor samples (evenly spaced along the move).
  const double u = p->profile.length > 0.0 ? q / p->profile.length * double(p->floor_z.size() - 1) : 0.0;
  const std::size_t i = std::min(static_cast<std::size_t>(u), p->floor_z.size() - 2);
  s.floor_z = p->floor_z[i] + (u - double(i)) * (p->floor_z[i + 1] - p->floor_z[i]);
  return s;
}

}  // namespace bimloc::sim
