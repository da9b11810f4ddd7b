#include "sim/runner/run_scenario.hpp"

#include "sim/metrics/map_error.hpp"
#include "sim/runner/evaluation.hpp"
#include "sim/base/outside_rooms.hpp"
#include "sim/base/room_lookup.hpp"
#include "sim/simulation/simulator.hpp"

#include <bimloc/bim/geometry2d.hpp>
#include <bimloc/geometry/planar_pose.hpp>

#include <algorithm>
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

// The S-Graph's wall estimates against the site's truth (how each wall was built).
static void scoreWalls(const std::vector<sgraph::WallDeviation>& estimates, const SiteTruth& truth, ScenarioResult& r) {
  constexpr int kWellSeen = 5;  // keyframe-plane factors: fewer, and the offset is barely estimated
  for (const auto& e : estimates) {
    ScenarioResult::WallEstimate w{e, std::nullopt, std::nullopt};
    if (const WallTruth* t = truth.findWall(e.wall_id); t && !t->missing) {
      w.true_offset_m = t->offset_m, w.true_angle_deg = t->angle_deg;
      if (e.observations >= kWellSeen && t->offset_m != 0.0)
        r.wall_offset_error_m = std::max(r.wall_offset_error_m.value_or(0.0), std::abs(e.offset_m - t->offset_m));
    }
    r.wall_deviations.push_back(w);
  }
}

std::string storeyKey(const bim::Building& building, std::size_t index) {
  const std::string& id = building.storeys.at(index).id;
  const auto same = std::count_if(building.storeys.begin(), building.storeys.end(), [&](const bim::Storey& s) { return s.id == id; });
  return !id.empty() && same == 1 ? id : std::to_string(index);
}

ScenarioResult runScenario(const Scenario& s, const World& world, const SnapshotHook& snapshot, std::vector<TraceRow>* trace,
                           std::vector<PoseRow>* poses) {
  const auto wall_start = std::chrono::steady_clock::now();
  ScenarioResult r;
  r.name = s.name;
  r.plan = s.world;
  r.seed = s.seed;
  r.start_room = s.start.kind == StartConfig::Kind::Pose ? std::string("(pose)") : s.start.room;

  const Simulator sim(s, world);
  const bim::Building& building = world.building();
  const bim::Storey& storey = building.storeys[sim.storey()];
  r.storey = storey.name;
  if (s.start.kind == StartConfig::Kind::OutsideRooms)
    r.start_room = "(" + outsideKind(storey, Eigen::Vector2d(sim.start().x, sim.start().y)) + ")";
  // The localizer: told the storey, or (storey auto) not, every storey that could hold the robot.
  const LocalizerSettings settings = localizerSettings(s);
  LocalizerConfig config = settings.config;
  r.storey_auto = settings.storey_auto;
  r.method = toString(config.method);
  if (!r.storey_auto) config.storey = storeyKey(building, sim.storey());
  std::optional<Localizer> localizer;
  try {
    localizer.emplace(building, s.sensor.T_base_lidar, config);
  } catch (const std::invalid_argument& e) {
    throw ScenarioError(s.file + ": " + e.what());
  }
  const std::vector<OdometrySample> odometry = sim.odometry();
  const auto odometryAt = [&](double t) {
    const auto k = static_cast<std::size_t>(std::llround(t * s.odometry.rate_hz));
    return odometry[std::min(k, odometry.size() - 1)].T_odom_base;
  };
  std::optional<Eigen::Isometry3d> estimate;  // the last step's, for the snapshots
  const auto moment = [&](const char* phase, double t, const Eigen::Isometry3d& truth) {
    const pf::StoreyBank* bank = localizer->filter();  // null for the peers (AMCL, NDT)
    snapshot({phase, t, bank ? &bank->filter() : nullptr, bank ? bank->leader() : sim.storey(), truth, localizer->tracker(), estimate});
  };
  if (snapshot) moment("initialization", 0.0, sim.trajectory().T_map_base(0.0));

  RunScore score(building, sim.storey());
  std::optional<pf::UpdateReport> last_verdict;  // the last update the path evidence spoke at
  std::size_t verdict_storey = sim.storey();     // ... and the storey it spoke of
  std::optional<pf::StoreyBankReport> last_bank;
  int updates = 0;
  MapErrorSampler map_error(building);
  Eigen::Isometry3d previous_truth = Eigen::Isometry3d::Identity();
  const double half_turn = 0.5 * sim.lidar().turnPeriod_s();
  for (std::size_t i = 0; i < sim.turnCount(); ++i) {
    const LidarScan scan = sim.turn(i);
    // The turn sweeps for a whole period: its planes are best explained by the mid-turn pose.
    const double t = scan.stamp_s + half_turn;
    const Eigen::Isometry3d T_odom_base = odometryAt(t);
    const auto step_start = std::chrono::steady_clock::now();
    const LocalizationResult step = localizer->step(t, T_odom_base, [&scan] { return scanPoints(scan); });
    estimate = step.T_map_base;
    const auto minute = static_cast<std::size_t>(t / 60.0);
    if (r.localizer_seconds_by_minute.size() <= minute) r.localizer_seconds_by_minute.resize(minute + 1, 0.0);
    r.localizer_seconds_by_minute[minute] += std::chrono::duration<double>(std::chrono::steady_clock::now() - step_start).count();
    ++updates;
    for (const auto& w : step.warnings) r.warnings.push_back("t=" + std::to_string(t) + ": " + w);
    const Eigen::Isometry3d truth = sim.trajectory().T_map_base(t);
    if (i > 0) r.path_length_m += (truth.translation() - previous_truth.translation()).head<2>().norm();
    previous_truth = truth;
    if (poses) poses->push_back({t, truth, step.T_map_base, RunScore::scored(step)});
    r.error_series.push_back({t, (step.T_map_base.translation() - truth.translation()).head<2>().norm(), yawErrorDeg(step.T_map_base, truth), step.state});
    if (step.filter) {
      const pf::StoreyBankReport& bank = *step.filter;
      if (r.storey_auto && bank.decided && !(last_bank && last_bank->decided)) r.storey_margin = bank.storey_margin;
      last_bank = bank;
      const pf::UpdateReport& report = bank.filter;
      if (trace && report.weighed)
        trace->push_back({t, planarPose(truth), planarPose(step.T_map_base), report,
                          r.storey_auto ? building.storeys[bank.leader].name : std::string(), bank.storey_margin});
      if (report.path_best) last_verdict = report, verdict_storey = bank.leader;
    }
    if (snapshot && updates == kClusteringUpdate && step.state == LocalizationState::Searching) moment("clustering", t, truth);
    map_error.step(step, s.sensor.T_base_lidar, [&scan] { return scanPoints(scan); });
    if (score.add(t, step, truth)) {
      if (step.filter) r.convergence_margin = step.filter->filter.path_margin;
      if (snapshot) moment("convergence", t, truth);
    }
  }
  const bool converged = score.converged();
  if (!converged && last_verdict) r.hypotheses = placesOf(*last_verdict, building.storeys[verdict_storey]);
  if (localizer->filter() && !localizer->filter()->storey() && r.storey_auto && last_bank)
    for (const auto& c : last_bank->candidates)
      r.storey_candidates.push_back({building.storeys[c.storey].name, c.converged, c.path_log_likelihood});
  // The last picture shows where the particles were left and why, or the graph the tracker built.
  if (snapshot && sim.turnCount() > 0 && (!converged || localizer->tracker())) {
    const double t_end = sim.lidar().turnPeriod_s() * (static_cast<double>(sim.turnCount()) - 0.5);
    moment("end", t_end, sim.trajectory().T_map_base(t_end));
  }
  score.finish(r);
  r.map_rmse_m = map_error.rmse_m();
  r.site = s.site.preset;
  if (const sgraph::SGraphTracker* tracker = localizer->tracker()) scoreWalls(tracker->wallDeviations(), sim.world().siteTruth(), r);
  r.sim_seconds = static_cast<double>(sim.turnCount()) * sim.lidar().turnPeriod_s();
  r.wall_seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - wall_start).count();
  judge(s, r);
  return r;
}

}  // namespace bimloc::sim
