#include "sim/runner/run_scenario.hpp"

#include "sim/simulation/simulator.hpp"

#include <bimloc/bim/geometry2d.hpp>

#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <cmath>

namespace bimloc::sim {
namespace {

constexpr double kFalsePositionM = 0.5;  // declared converged while farther off than this ...
constexpr double kFalseYawDeg = 10.0;    // ... or turned more than this: a false convergence
constexpr int kClusteringUpdate = 5;     // the snapshot of the clustering particles

double yawOf(const Eigen::Isometry3d& T) { return std::atan2(T.linear()(1, 0), T.linear()(0, 0)); }

double yawErrorDeg(const Eigen::Isometry3d& a, const Eigen::Isometry3d& b) {
  const double d = yawOf(a) - yawOf(b);
  return std::abs(std::atan2(std::sin(d), std::cos(d))) * 180.0 / M_PI;
}

std::string roomName(const bim::Storey& storey, int index) {
  return index < 0 ? std::string("(outside)") : storey.rooms[static_cast<std::size_t>(index)].name;
}

int roomOf(const bim::Storey& storey, const Eigen::Vector3d& p) {
  for (std::size_t r = 0; r < storey.rooms.size(); ++r)
    if (bim::pointInPolygon(storey.rooms[r].footprint, p.head<2>())) return static_cast<int>(r);
  return -1;
}

std::vector<Eigen::Vector3f> finitePoints(const LidarScan& scan) {
  std::vector<Eigen::Vector3f> points;
  points.reserve(scan.points.size());
  for (const auto& p : scan.points) points.emplace_back(p.x, p.y, p.z);
  return points;
}

void judge(const Scenario& s, ScenarioResult& r) {
  const Expectations& e = s.expect;
  if (e.converge && !r.converged) r.failures.push_back("did not converge");
  if (e.converge && r.convergence_time_s && *r.convergence_time_s > e.max_convergence_time_s)
    r.failures.push_back("converged after " + std::to_string(*r.convergence_time_s) + " s");
  if (r.false_convergence) r.failures.push_back("false convergence");
  if (r.converged && r.position_error_m > e.max_position_error_m)
    r.failures.push_back("final position error " + std::to_string(r.position_error_m) + " m");
  if (r.converged && r.yaw_error_deg > e.max_yaw_error_deg)
    r.failures.push_back("final yaw error " + std::to_string(r.yaw_error_deg) + " deg");
  if (r.ate_m && *r.ate_m > e.max_ate_m) r.failures.push_back("ATE " + std::to_string(*r.ate_m) + " m");
  if (!e.converge && r.converged && r.false_convergence) r.failures.push_back("converged falsely");
  r.passed = r.failures.empty();
}

}  // namespace

ScenarioResult runScenario(const Scenario& s, const World& world, const SnapshotHook& snapshot) {
  const auto wall_start = std::chrono::steady_clock::now();
  ScenarioResult r;
  r.name = s.name;
  r.plan = s.world;
  r.seed = s.seed;
  r.start_room = s.start.kind == StartConfig::Kind::Pose ? std::string("(pose)") : s.start.room;
  const LocalizerSettings settings = localizerSettings(s);
  r.method = settings.filter.use_rooms ? "pf" : "pf-no-rooms";

  const Simulator sim(s, world);
  const bim::Storey& storey = world.building().storeys[sim.storey()];
  r.storey = storey.name;
  pf::ParticleFilter filter(storey, s.sensor.T_base_lidar, settings.filter);
  const std::vector<OdometrySample> odometry = sim.odometry();
  const auto odometryAt = [&](double t) {
    const auto k = static_cast<std::size_t>(std::llround(t * s.odometry.rate_hz));
    return odometry[std::min(k, odometry.size() - 1)].T_odom_base;
  };
  if (snapshot) snapshot({"initialization", 0.0, &filter, sim.trajectory().T_map_base(0.0)});

  double sum_sq = 0;
  int after = 0, updates = 0;
  Eigen::Isometry3d truth = sim.trajectory().T_map_base(0.0), estimate = truth;
  const double half_turn = 0.5 * sim.lidar().turnPeriod_s();
  for (std::size_t i = 0; i < sim.turnCount(); ++i) {
    const LidarScan scan = sim.turn(i);
    // The turn sweeps for a whole period: its planes are best explained by the mid-turn pose.
    const double t = scan.stamp_s + half_turn;
    filter.predict(odometryAt(t));
    const auto planes = planes::extractPlanes(finitePoints(scan), settings.planes);
    const auto report = filter.update(planes.walls);
    if (std::getenv("BIMLOC_DEBUG_PF") && report.weighed) {
      const Eigen::Isometry3d tr = sim.trajectory().T_map_base(t);
      const auto truth_score = filter.score(tr.translation().x(), tr.translation().y(), yawOf(tr), planes.walls);
      const auto& b = filter.best();
      const auto best_score = filter.score(b.x, b.y, b.yaw, planes.walls);
      std::fprintf(stderr, "t=%.1f obs=%d ess=%.0f truth ll=%.1f assoc=%d | best (%.2f %.2f %.0f) ll=%.1f assoc=%d\n", t,
                   report.observations, report.ess, truth_score.first, truth_score.second, b.x, b.y, b.yaw * 57.3,
                   best_score.first, best_score.second);
    }
    ++updates;
    for (const auto& w : report.warnings) r.warnings.push_back("t=" + std::to_string(t) + ": " + w);
    truth = sim.trajectory().T_map_base(t);
    if (snapshot && updates == kClusteringUpdate && !filter.converged())
      snapshot({"clustering", t, &filter, truth});
    if (!filter.converged()) continue;
    estimate = filter.T_map_base();
    const double position_error = (estimate.translation() - truth.translation()).head<2>().norm();
    if (!r.converged) {
      r.converged = true;
      r.convergence_time_s = t;
      r.found_room = roomName(storey, filter.estimateRoom());
      r.true_room = roomName(storey, roomOf(storey, truth.translation()));
      if (snapshot) snapshot({"convergence", t, &filter, truth});
    }
    if (position_error > kFalsePositionM || yawErrorDeg(estimate, truth) > kFalseYawDeg) r.false_convergence = true;
    sum_sq += position_error * position_error;
    ++after;
  }
  if (!r.converged) {
    estimate = filter.T_map_base();
    r.true_room = roomName(storey, roomOf(storey, truth.translation()));
  }
  r.position_error_m = (estimate.translation() - truth.translation()).head<2>().norm();
  r.yaw_error_deg = yawErrorDeg(estimate, truth);
  if (after > 0) r.ate_m = std::sqrt(sum_sq / after);
  r.sim_seconds = static_cast<double>(sim.turnCount()) * sim.lidar().turnPeriod_s();
  r.wall_seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - wall_start).count();
  judge(s, r);
  return r;
}

}  // namespace bimloc::sim
