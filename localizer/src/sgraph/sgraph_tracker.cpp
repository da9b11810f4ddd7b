#include <bimloc/sgraph/sgraph_tracker.hpp>

#include "association.hpp"
#include "config_check.hpp"
#include "graph.hpp"
#include "loss_monitor.hpp"
#include "marginalization.hpp"
#include "plan_layers.hpp"
#include "room_association.hpp"
#include "window_solver.hpp"

#include <bimloc/geometry/planar_pose.hpp>

#include <chrono>
#include <cmath>
#include <cstdio>
#include <limits>
#include <optional>

namespace bimloc::sgraph {

using detail::between;
using detail::compose;

namespace {
constexpr double kDeg = M_PI / 180.0;

std::string format(const char* fmt, double a, double b = 0) {
  char text[200];
  std::snprintf(text, sizeof text, fmt, a, b);
  return text;
}
}  // namespace

struct SGraphTracker::Impl {
  Eigen::Isometry3d T_base_lidar;
  SGraphConfig config;
  Eigen::Isometry3d T_map_odom_initial;
  detail::Graph graph;
  std::vector<std::string> warnings;  // from the construction
  std::vector<std::string> wall_ids;
  bool reported_construction = false;
  std::optional<Eigen::Isometry3d> last_odom;
  double last_stamp = -std::numeric_limits<double>::infinity();
  bool jump_pending = false;
  std::optional<detail::LossMonitor> loss;

  // Steps of addScan, in the order of the paper's S-Graph stage.
  bool checkOdometry(double stamp_s, const Eigen::Isometry3d& T_odom_base, SGraphResult& r);
  Eigen::Vector3d predict(const Eigen::Vector3d& odom) const;
  bool needsKeyframe(const Eigen::Vector3d& odom) const;
  detail::Keyframe& addKeyframe(double stamp_s, const Eigen::Isometry3d& T_odom_base, const Eigen::Vector3d& predicted);
  std::vector<detail::ScanObservation> associate(detail::Keyframe& kf, const std::vector<planes::ObservedPlane>& walls, SGraphResult& r);
  detail::SolveReport optimize(const detail::Keyframe& kf, SGraphResult& r);
  void slide();
  void report(const Eigen::Vector3d& planar, const Eigen::Isometry3d& T_odom_base, SGraphResult& r) const;
};

SGraphTracker::SGraphTracker(const bim::Storey& storey, const Eigen::Isometry3d& T_base_lidar, const SGraphConfig& config,
                             const Eigen::Isometry3d& T_map_odom)
    : impl_(std::make_unique<Impl>()) {
  Impl& m = *impl_;
  m.T_base_lidar = T_base_lidar;
  m.config = detail::checkedConfig(config, m.warnings);
  m.loss.emplace(m.config);
  m.T_map_odom_initial = T_map_odom;
  if (!T_map_odom.matrix().allFinite()) {
    m.warnings.emplace_back("the initial map <- odom is not finite: using the identity");
    m.T_map_odom_initial = Eigen::Isometry3d::Identity();
  }
  if (!T_base_lidar.matrix().allFinite()) {
    m.warnings.emplace_back("the lidar mount is not finite: using the identity");
    m.T_base_lidar = Eigen::Isometry3d::Identity();
  }
  detail::buildPlanLayers(storey, m.graph, m.warnings);
  for (const bim::Wall& w : storey.walls) m.wall_ids.push_back(w.id);
}

SGraphTracker::~SGraphTracker() = default;
SGraphTracker::SGraphTracker(SGraphTracker&&) noexcept = default;

SGraphResult SGraphTracker::addScan(double stamp_s, const Eigen::Isometry3d& T_odom_base, const std::vector<planes::ObservedPlane>& walls) {
  Impl& m = *impl_;
  SGraphResult r;
  if (!m.reported_construction) r.warnings = m.warnings, m.reported_construction = true;
  if (!m.checkOdometry(stamp_s, T_odom_base, r)) {  // unusable: the last estimate stands
    r.T_map_odom = T_map_odom();
    r.T_map_base = m.last_odom ? r.T_map_odom * *m.last_odom : r.T_map_odom;
    r.keyframe = m.graph.window.empty() ? -1 : m.graph.window.back().id;
    r.window_keyframes = static_cast<int>(m.graph.window.size());
    r.state = m.loss->state();
    return r;
  }
  const Eigen::Vector3d odom = planarPose(T_odom_base);
  const Eigen::Vector3d predicted = m.predict(odom);
  if (!m.needsKeyframe(odom)) {
    m.report(predicted, T_odom_base, r);
    return r;
  }
  // keyframe -> associate (its measurements are the new factors) -> optimize window -> slide -> check loss
  detail::Keyframe& kf = m.addKeyframe(stamp_s, T_odom_base, predicted);
  const auto observations = m.associate(kf, walls, r);
  const detail::SolveReport solve = m.optimize(kf, r);
  m.slide();
  m.loss->update(detail::keyframeDoubt(m.graph, kf, observations, solve.usable, m.config), r.warnings);
  m.report(kf.planar(), T_odom_base, r);
  return r;
}

bool SGraphTracker::Impl::checkOdometry(double stamp_s, const Eigen::Isometry3d& T_odom_base, SGraphResult& r) {
  const Eigen::Matrix3d R = T_odom_base.linear();
  if (!T_odom_base.matrix().allFinite() || (R.transpose() * R - Eigen::Matrix3d::Identity()).norm() > 1e-3) {
    r.warnings.emplace_back("scan at " + format("%.3f s", stamp_s) + ": the odometry pose is not a finite rigid transform, scan skipped");
    return false;
  }
  if (!std::isfinite(stamp_s) || stamp_s < last_stamp)
    r.warnings.push_back("scan at " + format("%.3f s", stamp_s) + ": time stamp not after the previous one (" + format("%.3f s", last_stamp) + ")");
  else
    last_stamp = stamp_s;
  if (last_odom) {
    const Eigen::Vector3d step = planarPose(last_odom->inverse() * T_odom_base);
    if (step.head<2>().norm() > config.odometry_jump_m || std::abs(step.z()) > config.odometry_jump_deg * kDeg) {
      r.warnings.push_back("odometry jumped by " + format("%.2f m and %.1f deg", step.head<2>().norm(), std::abs(step.z()) / kDeg) +
                           " between two scans: the next keyframe's odometry link is weak");
      jump_pending = true;
    }
  }
  last_odom = T_odom_base;
  return true;
}

Eigen::Vector3d SGraphTracker::Impl::predict(const Eigen::Vector3d& odom) const {
  if (graph.window.empty()) return planarPose(T_map_odom_initial * last_odom.value());
  const detail::Keyframe& last = graph.window.back();
  return compose(last.planar(), between(last.odom, odom));
}

bool SGraphTracker::Impl::needsKeyframe(const Eigen::Vector3d& odom) const {
  if (graph.window.empty() || jump_pending) return true;
  const Eigen::Vector3d u = between(graph.window.back().odom, odom);
  return u.head<2>().norm() >= config.keyframe_spacing_m || std::abs(u.z()) >= config.keyframe_spacing_deg * kDeg;
}

detail::Keyframe& SGraphTracker::Impl::addKeyframe(double stamp_s, const Eigen::Isometry3d& T_odom_base, const Eigen::Vector3d& predicted) {
  detail::Keyframe kf;
  kf.id = graph.next_keyframe_id++;
  kf.stamp_s = stamp_s;
  kf.T_odom_base = T_odom_base;
  kf.odom = planarPose(T_odom_base);
  kf.pose = {predicted.x(), predicted.y(), predicted.z()};
  kf.predicted = predicted;
  kf.tilt = detail::tiltOf(T_odom_base.linear());
  kf.z_map = (T_map_odom_initial * T_odom_base).translation().z();
  kf.A = kf.tilt * T_base_lidar.linear();
  kf.b = kf.tilt * T_base_lidar.translation();
  kf.odometry_jump = jump_pending && !graph.window.empty();
  jump_pending = false;
  if (!graph.floor_base_z) graph.floor_base_z = kf.z_map;  // handed over (or arrived) standing on the floor
  if (graph.window.empty()) {  // the first keyframe: the particle filter's pose, to its precision
    graph.prior = detail::posePrior(predicted, {config.initial_sigma_xy_m, config.initial_sigma_xy_m, config.initial_sigma_yaw_deg * kDeg});
  }
  KeyframeInfo info;
  info.id = kf.id;
  info.stamp_s = stamp_s;
  info.T_map_base = kf.T_map_base();
  info.in_window = true;
  graph.history.push_back(info);
  graph.window.push_back(std::move(kf));
  return graph.window.back();
}

// Planes with the plan's walls and the new planes (paper, "Plane Association"), then rooms
// with the plan's rooms ("Room Association"), which may merge new planes into plan walls.
std::vector<detail::ScanObservation> SGraphTracker::Impl::associate(detail::Keyframe& kf, const std::vector<planes::ObservedPlane>& walls,
                                                                    SGraphResult& r) {
  auto observations = detail::prepareObservations(kf, walls, config, r);
  detail::associate(graph, kf, observations, config, r);
  detail::associateRooms(graph, kf, config, r);
  kf.plan_walls = 0;
  for (const auto& p : kf.planes) kf.plan_walls += graph.nodes[static_cast<std::size_t>(p.node)].kind == detail::WallNode::Kind::Plan;
  return observations;
}

detail::SolveReport SGraphTracker::Impl::optimize(const detail::Keyframe& kf, SGraphResult& r) {
  const detail::SolveReport solve = detail::optimizeWindow(graph, config);
  if (!solve.usable) r.warnings.push_back("keyframe " + std::to_string(kf.id) + ": the optimization failed (" + solve.message + "), estimate kept");
  r.keyframe_added = true;
  r.iterations = solve.iterations;
  r.initial_cost = solve.initial_cost;
  r.final_cost = solve.final_cost;
  r.solve_time_s = solve.time_s;
  r.covariance = solve.newest_covariance;
  return solve;
}

// Marginalize what leaves the window; the history keeps every keyframe's latest pose.
void SGraphTracker::Impl::slide() {
  while (static_cast<int>(graph.window.size()) > config.window_keyframes) detail::marginalizeOldest(graph, config);
  for (const detail::Keyframe& w : graph.window) {
    KeyframeInfo& info = graph.history[static_cast<std::size_t>(w.id)];
    info.T_map_base = w.T_map_base();
    info.plan_walls = w.plan_walls;
  }
}

void SGraphTracker::Impl::report(const Eigen::Vector3d& planar, const Eigen::Isometry3d& T_odom_base, SGraphResult& r) const {
  r.T_map_base.setIdentity();
  r.T_map_base.linear() = Eigen::AngleAxisd(planar.z(), Eigen::Vector3d::UnitZ()).toRotationMatrix() * detail::tiltOf(T_odom_base.linear());
  r.T_map_base.translation() = Eigen::Vector3d(planar.x(), planar.y(), (T_map_odom_initial * T_odom_base).translation().z());
  r.T_map_odom = r.T_map_base * T_odom_base.inverse();
  r.keyframe = graph.window.empty() ? -1 : graph.window.back().id;
  r.window_keyframes = static_cast<int>(graph.window.size());
  r.state = loss->state();
}

bool SGraphTracker::wantsObservations(const Eigen::Isometry3d& T_odom_base) const {
  const Impl& m = *impl_;
  if (!T_odom_base.matrix().allFinite()) return false;
  if (m.last_odom) {
    const Eigen::Vector3d step = planarPose(m.last_odom->inverse() * T_odom_base);
    if (step.head<2>().norm() > m.config.odometry_jump_m || std::abs(step.z()) > m.config.odometry_jump_deg * kDeg) return true;
  }
  return m.needsKeyframe(planarPose(T_odom_base));
}

TrackingState SGraphTracker::state() const { return impl_->loss->state(); }

Eigen::Isometry3d SGraphTracker::T_map_odom() const {
  const auto& g = impl_->graph;
  if (g.window.empty()) return impl_->T_map_odom_initial;
  const auto& kf = g.window.back();
  return kf.T_map_base() * kf.T_odom_base.inverse();
}

std::vector<WallDeviation> SGraphTracker::wallDeviations() const {
  std::vector<WallDeviation> out;
  for (const auto& node : impl_->graph.nodes) {
    if (node.kind != detail::WallNode::Kind::Plan || !node.active || node.observations == 0) continue;
    WallDeviation w;
    w.wall = node.wall;
    w.wall_id = impl_->wall_ids[static_cast<std::size_t>(node.wall)];
    w.offset_m = node.params[0];
    w.angle_deg = node.params[1] / kDeg;
    w.thickness_change_m = node.params[2];
    w.observations = node.observations;
    out.push_back(w);
  }
  return out;
}

std::vector<NewPlane> SGraphTracker::newPlanes() const {
  std::vector<NewPlane> out;
  for (const auto& node : impl_->graph.nodes) {
    if (node.kind != detail::WallNode::Kind::New || !node.active) continue;
    NewPlane p;
    p.id = node.new_id;
    const Eigen::Vector2d n = node.normal(0);
    p.normal = Eigen::Vector3d(n.x(), n.y(), 0.0);
    p.d = node.d(0);
    p.start = node.start[0];
    p.end = node.end[0];
    p.observations = node.observations;
    out.push_back(p);
  }
  return out;
}

std::vector<KeyframeInfo> SGraphTracker::keyframes() const { return impl_->graph.history; }

std::vector<RoomNode> SGraphTracker::rooms() const {
  std::vector<RoomNode> out;
  for (const auto& room : impl_->graph.rooms) {
    RoomNode r;
    r.room = room.room;
    r.name = room.name;
    r.corridor = room.corridor;
    r.plan_centre = room.plan_centre;
    r.centre = Eigen::Vector2d(room.centre[0], room.centre[1]);
    for (const auto& f : room.pairs) r.walls.push_back(impl_->graph.nodes[static_cast<std::size_t>(f.node)].wall);
    out.push_back(r);
  }
  return out;
}

const std::vector<std::string>& SGraphTracker::warnings() const { return impl_->warnings; }

}  // namespace bimloc::sgraph
