#include "sim/runner/run_scenario.hpp"

#include "sim/runner/evaluation.hpp"
#include "sim/base/outside_rooms.hpp"
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
  // Places of one storey: the path evidence weighs places of other storeys apart (StoreyBank).
  std::vector<std::pair<Eigen::Vector3d, double>> all{{*report.path_best, 0.0}};
  all.insert(all.end(), report.path_rivals.begin(), report.path_rivals.end());
  double sum = 0;
  for (const auto& [pose, margin] : all) sum += std::exp(-std::min(margin, 700.0));
  std::vector<ScenarioResult::Place> places;
  for (const auto& [pose, margin] : all) {
    const bim::Room* room = roomAt(storey, pose.head<2>());
    places.push_back({pose.x(), pose.y(), pose.z() * 180.0 / M_PI, std::exp(-std::min(margin, 700.0)) / sum,
                      room ? room->name : std::string("(outside)"), storey.name});
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
  const bim::Building& building = world.building();
  const bim::Storey& storey = building.storeys[sim.storey()];
  r.storey = storey.name;
  if (s.start.kind == StartConfig::Kind::OutsideRooms)
    r.start_room = "(" + outsideKind(storey, Eigen::Vector2d(sim.start().x, sim.start().y)) + ")";
  // The localizer: told the storey, or (storey auto) every storey that could hold the robot.
  r.storey_auto = settings.storey_auto;
  const std::vector<std::size_t> storeys =
      settings.storey_auto ? pf::StoreyBank::candidateStoreys(building) : std::vector<std::size_t>{sim.storey()};
  if (storeys.empty()) throw ScenarioError(s.file + ": storey auto: no storey of the plan has both walls and rooms");
  pf::StoreyBank filter(building, storeys, s.sensor.T_base_lidar, settings.filter);
  const std::vector<OdometrySample> odometry = sim.odometry();
  const auto odometryAt = [&](double t) {
    const auto k = static_cast<std::size_t>(std::llround(t * s.odometry.rate_hz));
    return odometry[std::min(k, odometry.size() - 1)].T_odom_base;
  };
  const auto moment = [&](const char* phase, double t, const Eigen::Isometry3d& truth) {
    snapshot({phase, t, &filter.filter(), filter.leader(), truth});
  };
  if (snapshot) moment("initialization", 0.0, sim.trajectory().T_map_base(0.0));

  RunScore score(building, sim.storey());
  std::optional<pf::UpdateReport> last_verdict;  // the last update the path evidence spoke at
  std::size_t verdict_storey = sim.storey();     // ... and the storey it spoke of
  pf::StoreyBankReport last;
  int updates = 0;
  const double half_turn = 0.5 * sim.lidar().turnPeriod_s();
  for (std::size_t i = 0; i < sim.turnCount(); ++i) {
    const LidarScan scan = sim.turn(i);
    // The turn sweeps for a whole period: its planes are best explained by the mid-turn pose.
    const double t = scan.stamp_s + half_turn;
    filter.predict(odometryAt(t));
    // Planes only for the scans the filter weighs: the others it would not look at.
    const pf::StoreyBankReport bank = filter.update(filter.wantsObservations()
                                                        ? planes::extractPlanes(scanPoints(scan), settings.planes).walls
                                                        : std::vector<planes::ObservedPlane>{});
    const pf::UpdateReport& report = bank.filter;
    if (r.storey_auto && bank.decided && !last.decided) r.storey_margin = bank.storey_margin;
    last = bank;
    ++updates;
    for (const auto& w : report.warnings) r.warnings.push_back("t=" + std::to_string(t) + ": " + w);
    const Eigen::Isometry3d truth = sim.trajectory().T_map_base(t);
    if (trace && report.weighed)
      trace->push_back({t, planarPose(truth), planarPose(filter.T_map_base()), report,
                        r.storey_auto ? building.storeys[bank.leader].name : std::string(), bank.storey_margin});
    if (snapshot && updates == kClusteringUpdate && !filter.converged()) moment("clustering", t, truth);
    if (report.path_best) last_verdict = report, verdict_storey = bank.leader;
    if (score.add(t, filter, truth)) {
      r.convergence_margin = report.path_margin;
      if (snapshot) moment("convergence", t, truth);
    }
  }
  if (!filter.converged() && last_verdict) r.hypotheses = placesOf(*last_verdict, building.storeys[verdict_storey]);
  if (!filter.storey() && r.storey_auto)
    for (const auto& c : last.candidates)
      r.storey_candidates.push_back({building.storeys[c.storey].name, c.converged, c.path_log_likelihood});
  // Not converged: the last picture shows where the particles were left, and why.
  if (snapshot && !filter.converged() && sim.turnCount() > 0) {
    const double t_end = sim.lidar().turnPeriod_s() * (static_cast<double>(sim.turnCount()) - 0.5);
    moment("end", t_end, sim.trajectory().T_map_base(t_end));
  }
  score.finish(filter, r);
  r.sim_seconds = static_cast<double>(sim.turnCount()) * sim.lidar().turnPeriod_s();
  r.wall_seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - wall_start).count();
  judge(s, r);
  return r;
}

}  // namespace bimloc::sim
