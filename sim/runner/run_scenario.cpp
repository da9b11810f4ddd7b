#include "sim/runner/run_scenario.hpp"

#include "sim/dataset/deskew.hpp"
#include "sim/lidar/vlp16.hpp"
#include "sim/runner/guided_walk.hpp"
#include "sim/runner/method_run.hpp"
#include "sim/base/outside_rooms.hpp"

#include <bimloc/geometry/planar_pose.hpp>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <ctime>

namespace bimloc::sim {

double processCpuSeconds() {
  timespec t{};
  clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &t);
  return static_cast<double>(t.tv_sec) + 1e-9 * static_cast<double>(t.tv_nsec);
}

namespace {

// One simulation, every localizer stepped on each turn in turn: the same scans, the same
// odometry. hooks[k] takes localizer k's snapshots (none past the end of `hooks`, or empty);
// the trace and the poses follow the first localizer.
std::vector<ScenarioResult> runLoop(const Scenario& s, const World& world, const std::vector<LocalizerSettings>& settings,
                                    const std::vector<SnapshotHook>& hooks, std::vector<TraceRow>* trace,
                                    std::vector<PoseRow>* poses = nullptr, bool with_oracle = false) {
  const auto wall_start = std::chrono::steady_clock::now();
  ScenarioResult shared;
  shared.name = s.name;
  shared.plan = s.world;
  shared.seed = s.seed;
  shared.start_room = s.start.kind == StartConfig::Kind::Pose ? std::string("(pose)") : s.start.room;

  const Simulator sim(s, world);
  shared.setup_seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - wall_start).count();
  const bim::Storey& storey = world.building().storeys[sim.storey()];
  shared.storey = world.building().storeyLabel(sim.storey());
  if (s.start.kind == StartConfig::Kind::OutsideRooms)
    shared.start_room = "(" + outsideKind(storey, Eigen::Vector2d(sim.start().x, sim.start().y)) + ")";
  std::vector<MethodRun> runs;
  runs.reserve(settings.size());
  for (const auto& one : settings) runs.emplace_back(s, world, sim, one, shared);
  // The snapshot hooks by reference: each counts its pictures.
  const SnapshotHook none;
  const auto hookOf = [&](std::size_t k) -> const SnapshotHook& { return k < hooks.size() ? hooks[k] : none; };
  // The base: its planned trajectory, or steered step by step where the first localizer
  // suggests looking (motion.disambiguate): then the odometry is drawn as the base goes.
  std::optional<GuidedWalk> walk;
  if (s.motion.disambiguate) walk.emplace(sim);
  const auto truthAt = [&](double t) { return walk ? walk->T_map_base(t) : sim.trajectory().T_map_base(t); };
  for (std::size_t k = 0; k < runs.size(); ++k)
    if (hookOf(k)) runs[k].snapshotNow("initialization", 0.0, truthAt(0.0), hookOf(k));

  std::vector<OdometrySample> odometry = walk ? std::vector<OdometrySample>() : sim.odometry();
  std::optional<NoisyOdometry> odometry_model;
  if (walk) odometry_model.emplace(sim.odometryModel(sim.trajectory().floor_z(0.0)));
  // The reading k (at k / rate_hz); a guided walk's are drawn as the base goes, up to k.
  const auto readingAt = [&](std::size_t k) {
    while (odometry_model && odometry.size() <= k) {
      const double tk = static_cast<double>(odometry.size()) / s.odometry.rate_hz;
      odometry.push_back(odometry_model->step(tk, walk->T_map_base(tk)));
    }
    return odometry[std::min(k, odometry.size() - 1)];
  };
  const auto readingIndex = [&](double t) { return static_cast<std::size_t>(std::llround(t * s.odometry.rate_hz)); };
  // De-skew (sensor.deskew): the readings from the turn's first firing to its last, never past
  // its end (a guided walk's poses after it are not decided yet), and never the truth.
  const bool deskew_turns = s.sensor.deskew && s.sensor.motion_distortion;
  const auto readingsOver = [&](double t0_s, double t1_s) {
    std::vector<StampedPose> span;
    const double rate = s.odometry.rate_hz;
    const auto k0 = static_cast<std::size_t>(std::max(0.0, std::floor(t0_s * rate + 1e-6)));
    const auto k1 = static_cast<std::size_t>(std::max(0.0, std::floor(t1_s * rate + 1e-6)));
    for (std::size_t k = k0; k <= k1; ++k) {
      const OdometrySample o = readingAt(k);
      if (span.empty() || o.stamp_s > span.back().stamp_s) span.push_back({o.stamp_s, o.T_odom_base});
    }
    return span;
  };
  // The oracle's record of the run (bounded: keyframes of a few hundred band points), and the
  // floor under the start and the true start it needs.
  std::optional<oracle::KeyframeRecorder> keyframes;
  double floor_z = storey.elevation_m;
  Eigen::Vector3d truth_start = Eigen::Vector3d::Zero();
  double path_length_m = 0;
  Eigen::Isometry3d previous_truth = Eigen::Isometry3d::Identity();
  const double half_turn = 0.5 * sim.lidar().turnPeriod_s();
  double search_cpu = 0, tracking_cpu = 0, search_sim = 0, tracking_sim = 0;
  ScenarioResult::GuideUse guide_use;
  for (std::size_t i = 0; i < sim.turnCount(); ++i) {
    const double cpu_turn = processCpuSeconds();
    const bool searching = runs.empty() || runs.front().searching();
    // The turn is cast when a localizer (or the oracle) first reads its points, as its de-skew
    // is: a searching filter weighs every 0.2 m or 20 deg, a tracker at its keyframes, and most
    // turns are read by none. A turn is a pure function of its index and the base's poses over
    // it (its noise and site drawn from the turn's own seed), so a turn cast or skipped changes
    // no other; the poses over it are decided before the step (the walk follows after it).
    const double stamp_s = sim.turnStamp(i);
    const auto castTurn = [&] { return walk ? sim.turnAlong(i, [&walk](double t) { return walk->T_map_base(t); }) : sim.turn(i); };
    // The turn sweeps for a whole period: its planes are best explained by the mid-turn pose.
    const double t = stamp_s + half_turn;
    const OdometrySample reading = readingAt(readingIndex(t));
    const Eigen::Isometry3d T_odom_base = reading.T_odom_base;
    const Eigen::Isometry3d truth = truthAt(t);
    if (i > 0) path_length_m += (truth.translation() - previous_truth.translation()).head<2>().norm();
    previous_truth = truth;
    std::optional<std::vector<Eigen::Vector3f>> points;  // made once a turn, when a localizer reads them
    const Localizer::PointSource source = [&] {
      // De-skewed into the lidar frame at the reading the localizer is given with the turn.
      // Non-finite and out-of-range points are the plane extraction's to drop.
      // One pose per firing cycle: the simulator casts a cycle from one pose (deskew.hpp).
      if (!points)
        points = deskewedTurn(castTurn(), deskew_turns ? readingsOver(stamp_s, stamp_s + 2 * half_turn) : std::vector<StampedPose>{},
                              reading.stamp_s, s.sensor.T_base_lidar, kVlp16CyclePeriod_s);
      return *points;
    };
    if (with_oracle) {
      if (!keyframes) {
        const Eigen::Vector3d at = truth.translation();
        if (!world.floorBelow(sim.storey(), at, 3.0, &floor_z)) floor_z = storey.elevation_m;
        keyframes.emplace(oracle::OracleConfig{}, s.sensor.T_base_lidar, at.z() - floor_z);
        truth_start = planarPose(truth);
      }
      keyframes->add(t, T_odom_base, source);
    }
    for (std::size_t k = 0; k < runs.size(); ++k) runs[k].step(t, T_odom_base, source, truth, hookOf(k), k == 0 ? trace : nullptr, k == 0 ? poses : nullptr);
    (searching ? search_cpu : tracking_cpu) += processCpuSeconds() - cpu_turn;
    (searching ? search_sim : tracking_sim) += sim.lidar().turnPeriod_s();
    // The poses of this whole turn are cast: the walk may change course only after it.
    if (walk) {
      walk->follow(runs[0].lastState(), runs[0].lastGoal(), T_odom_base, truth, sim.turnStamp(i + 1));
      if (runs[0].lastState() == LocalizationState::Searching) {
        guide_use.place_steps += runs[0].lastPlaces() >= 2 ? 1 : 0;
        guide_use.goal_steps += runs[0].lastGoal() ? 1 : 0;
        if (runs[0].lastGoal() && !guide_use.first_goal_s) guide_use.first_goal_s = t;
      }
    }
  }
  const double t_end = sim.lidar().turnPeriod_s() * (static_cast<double>(sim.turnCount()) - 0.5);
  const Eigen::Isometry3d truth_end = truthAt(std::max(0.0, t_end));
  std::optional<oracle::OracleVerdict> verdict;
  if (keyframes)
    verdict = oracle::decideWhen(oracle::withEveryWall(world.building(), sim.storey()), floor_z, keyframes->keyframes(), truth_start);
  std::vector<ScenarioResult> results;
  for (std::size_t k = 0; k < runs.size(); ++k) {
    ScenarioResult r = runs[k].finish(t_end, truth_end, hookOf(k));
    r.path_length_m = path_length_m;
    if (walk && k == 0) {  // the walk follows the first method's goals
      guide_use.goals_taken = walk->goalsTaken();
      r.guide = guide_use;
    }
    r.sim_seconds = static_cast<double>(sim.turnCount()) * sim.lidar().turnPeriod_s();
    // The oracle's own cost is in r.oracle->seconds, not in the run's.
    r.wall_seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - wall_start).count() -
                     (verdict ? verdict->seconds : 0.0);
    r.oracle = verdict;
    r.search_cpu_seconds = search_cpu, r.tracking_cpu_seconds = tracking_cpu;
    r.search_sim_seconds = search_sim, r.tracking_sim_seconds = tracking_sim;
    results.push_back(std::move(r));
  }
  return results;
}

}  // namespace

std::string storeyKey(const bim::Building& building, std::size_t index) {
  const std::string& id = building.storeys.at(index).id;
  const auto same = std::count_if(building.storeys.begin(), building.storeys.end(), [&](const bim::Storey& s) { return s.id == id; });
  return !id.empty() && same == 1 ? id : std::to_string(index);
}

ScenarioResult runScenario(const Scenario& s, const World& world, const SnapshotHook& snapshot, std::vector<TraceRow>* trace,
                           std::vector<PoseRow>* poses, bool with_oracle) {
  return runLoop(s, world, {localizerSettings(s)}, {snapshot}, trace, poses, with_oracle).front();
}

std::vector<ScenarioResult> runScenarioMethods(const Scenario& s, const World& world, const std::vector<std::string>& methods,
                                               const std::vector<SnapshotHook>& snapshots) {
  std::vector<LocalizerSettings> settings;
  for (const auto& method : methods) {
    Scenario with = s;  // the scenario's own localizer settings, its method replaced
    with.localizer["method"] = method;
    settings.push_back(localizerSettings(with));
  }
  return runLoop(s, world, settings, snapshots, nullptr);
}

}  // namespace bimloc::sim
