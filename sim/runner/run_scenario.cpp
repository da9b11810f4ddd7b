#include "sim/runner/run_scenario.hpp"

#include "sim/runner/evaluation.hpp"
#include "sim/base/room_lookup.hpp"
#include "sim/simulation/simulator.hpp"

#include <bimloc/bim/geometry2d.hpp>
#include <bimloc/geometry/planar_pose.hpp>

#include <chrono>
#include <cmath>

namespace bimloc::sim {
namespace {

constexpr int kClusteringUpdate = 5;  // the snapshot of the clustering particles

// The turn's x, y, z; non-finite and out-of-range points are the plane extraction's to drop.
std::vector<Eigen::Vector3f> scanPoints(const LidarScan& scan) {
  std::vector<Eigen::Vector3f> points;
  points.reserve(scan.points.size());
  for (const auto& p : scan.points) points.emplace_back(p.x, p.y, p.z);
  return points;
}

// The path evidence's distinct places, with their rooms and relative weights.
std::vector<ScenarioResult::Place> placesOf(const pf::UpdateReport& report, const bim::Storey& storey) {
  std::vector<std::pair<Eigen::Vector3d, double>> all{{*report.path_best, 0.0}};
  all.insert(all.end(), report.path_rivals.begin(), report.path_rivals.end());
  double sum = 0;
  for (const auto& [pose, margin] : all) sum += std::exp(-std::min(margin, 700.0));
  std::vector<ScenarioResult::Place> places;
  for (const auto& [pose, margin] : all) {
    const bim::Room* room = roomAt(storey, pose.head<2>());
    places.push_back({pose.x(), pose.y(), pose.z() * 180.0 / M_PI, std::exp(-std::min(margin, 700.0)) / sum,
                      room ? room->name : std::string("(outside)")});
  }
  return places;
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

ScenarioResult runScenario(const Scenario& s, const World& world, const SnapshotHook& snapshot, std::vector<TraceRow>* trace) {
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

  RunScore score(storey);
  std::optional<pf::UpdateReport> last_verdict;  // the last update the path evidence spoke at
  int updates = 0;
  const double half_turn = 0.5 * sim.lidar().turnPeriod_s();
  for (std::size_t i = 0; i < sim.turnCount(); ++i) {
    const LidarScan scan = sim.turn(i);
    // The turn sweeps for a whole period: its planes are best explained by the mid-turn pose.
    const double t = scan.stamp_s + half_turn;
    filter.predict(odometryAt(t));
    // Planes only for the scans the filter weighs: the others it would not look at.
    const auto report = filter.update(filter.wantsObservations()
                                          ? planes::extractPlanes(scanPoints(scan), settings.planes).walls
                                          : std::vector<planes::ObservedPlane>{});
    ++updates;
    for (const auto& w : report.warnings) r.warnings.push_back("t=" + std::to_string(t) + ": " + w);
    const Eigen::Isometry3d truth = sim.trajectory().T_map_base(t);
    if (trace && report.weighed) trace->push_back({t, planarPose(truth), planarPose(filter.T_map_base()), report});
    if (snapshot && updates == kClusteringUpdate && !filter.converged()) snapshot({"clustering", t, &filter, truth});
    if (report.path_best) last_verdict = report;
    if (score.add(t, filter, truth)) {
      r.convergence_margin = report.path_margin;
      if (snapshot) snapshot({"convergence", t, &filter, truth});
    }
  }
  if (!filter.converged() && last_verdict) r.hypotheses = placesOf(*last_verdict, storey);
  // Not converged: the last picture shows where the particles were left, and why.
  if (snapshot && !filter.converged() && sim.turnCount() > 0) {
    const double t_end = sim.lidar().turnPeriod_s() * (static_cast<double>(sim.turnCount()) - 0.5);
    snapshot({"end", t_end, &filter, sim.trajectory().T_map_base(t_end)});
  }
  score.finish(filter, r);
  r.sim_seconds = static_cast<double>(sim.turnCount()) * sim.lidar().turnPeriod_s();
  r.wall_seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - wall_start).count();
  judge(s, r);
  return r;
}

}  // namespace bimloc::sim
