#include "sim/runner/method_run.hpp"

#include "sim/runner/path_places.hpp"

#include <bimloc/bim/geometry2d.hpp>
#include <bimloc/geometry/planar_pose.hpp>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdlib>

namespace bimloc::sim {
namespace {

constexpr int kClusteringUpdate = 5;  // the snapshot of the clustering particles

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

// The S-Graph's wall estimates against the site's truth (how each wall was built).
void scoreWalls(const std::vector<sgraph::WallDeviation>& estimates, const SiteTruth& truth, ScenarioResult& r) {
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

}  // namespace

MethodRun::MethodRun(const Scenario& s, const World& plan, const Simulator& sim, const LocalizerSettings& settings,
                     const ScenarioResult& shared)
    : scenario_(s), building_(plan.building()), sim_(sim), r_(shared), score_(building_, sim.storey()), map_error_(building_),
      verdict_storey_(sim.storey()) {
  // The localizer: told the storey, or (storey auto) not, every storey that could hold the robot.
  const bim::Building& building = building_;
  LocalizerConfig config = settings.config;
  r_.storey_auto = settings.storey_auto;
  r_.method = toString(config.method);
  if (!r_.storey_auto) config.storey = storeyKey(building, sim.storey());
  config.points_deskewed = s.sensor.deskew && s.sensor.motion_distortion;  // as the loop gives them (run_scenario.cpp)
  // The guide's goal is read only by a base that walks by it (motion disambiguate: GuidedWalk);
  // a tour never reads it, and no report, trace or picture shows it, while planning it cost an
  // eighth of a 100-room floor's search (docs/results/2026-11-28-h28speed9.md). The places are
  // listed either way (the trace and the end of a run show them): only the goal is not planned.
  config.guide.enabled = config.guide.enabled && s.motion.disambiguate;
  if (s.barometer.enabled) barometer_.emplace(s.barometer, s.seed);
  try {
    localizer_.emplace(building, s.sensor.T_base_lidar, config);
  } catch (const std::invalid_argument& e) {
    throw ScenarioError(s.file + ": " + e.what());
  }
}

void MethodRun::snapshotNow(const char* phase, double t, const Eigen::Isometry3d& truth, const SnapshotHook& snapshot) const {
  const pf::StoreyBank* bank = localizer_->filter();  // null for the peers (AMCL, NDT)
  // The storey being tracked (it follows the robot up and down the stairs), else the filter's leading one.
  const std::size_t storey = storey_ ? *storey_ : bank ? bank->leader() : sim_.storey();
  const bool filter_there = bank && bank->leader() == storey;
  snapshot({phase, t, filter_there ? &bank->filter() : nullptr, storey, truth, localizer_->tracker(), estimate_});
}

void MethodRun::step(double t, const Eigen::Isometry3d& T_odom_base, const Localizer::PointSource& points,
                     const Eigen::Isometry3d& truth, const SnapshotHook& snapshot, std::vector<TraceRow>* trace,
                     std::vector<PoseRow>* poses) {
  const bim::Building& building = building_;
  const auto step_start = std::chrono::steady_clock::now();
  // The barometer's altitude first (issue 31): every method reads the same (its own stream of the seed).
  if (barometer_) localizer_->observeAltitude(t, barometer_->read(t, truth.translation().z()), barometer_->sigma_m());
  // The turn is cast and de-skewed when a localizer first reads it (run_scenario.cpp), inside
  // its step: the simulator's time, not the localizer's, whichever method reads first.
  double turn_seconds = 0;
  const Localizer::PointSource timed = [&] {
    const auto turn_start = std::chrono::steady_clock::now();
    std::vector<Eigen::Vector3f> read = points();
    turn_seconds += std::chrono::duration<double>(std::chrono::steady_clock::now() - turn_start).count();
    return read;
  };
  const LocalizationResult step = localizer_->step(t, T_odom_base, timed);
  estimate_ = step.T_map_base;
  storey_ = step.storey;
  last_state_ = step.state, last_goal_ = step.goal, last_places_ = step.places.size();
  const auto minute = static_cast<std::size_t>(t / 60.0);
  if (r_.localizer_seconds_by_minute.size() <= minute) r_.localizer_seconds_by_minute.resize(minute + 1, 0.0);
  r_.localizer_seconds_by_minute[minute] +=
      std::chrono::duration<double>(std::chrono::steady_clock::now() - step_start).count() - turn_seconds;
  ++updates_;
  searching_ = step.state == LocalizationState::Searching;
  for (const auto& w : step.warnings) r_.warnings.push_back("t=" + std::to_string(t) + ": " + w);
  if (poses) poses->push_back({t, truth, step.T_map_base, RunScore::scored(step)});
  r_.error_series.push_back({t, (step.T_map_base.translation() - truth.translation()).head<2>().norm(),
                             yawErrorDeg(step.T_map_base, truth), step.state, 0, false, step.storey});
  if (step.filter) {
    const pf::StoreyBankReport& bank = *step.filter;
    if (r_.storey_auto && bank.decided && !(last_bank_ && last_bank_->decided)) r_.storey_margin = bank.storey_margin;
    last_bank_ = bank;
    const pf::UpdateReport& report = bank.filter;
    r_.verdicts_bound_held += report.path_bound_held, r_.verdicts_fit_lowered += report.path_fit_lowered;
    if (report.path_bound_held > 0 && !r_.first_bound_held_s) r_.first_bound_held_s = t;
    if (report.path_fit_lowered > 0 && !r_.first_fit_lowered_s) r_.first_fit_lowered_s = t;
    if (trace && report.weighed)
      trace->push_back({t, planarPose(truth), planarPose(step.T_map_base), report,
                        r_.storey_auto ? building.storeyLabel(bank.leader) : std::string(), bank.storey_margin,
                        step.places.size(), step.goal});
    // The places listed at the end: the last fitted (the localizer fits them at its places_interval_s).
    if (report.path_best && report.places_fitted) last_verdict_ = report, verdict_storey_ = bank.leader;
  }
  if (snapshot && updates_ == kClusteringUpdate && step.state == LocalizationState::Searching)
    snapshotNow("clustering", t, truth, snapshot);
  map_error_.step(step, scenario_.sensor.T_base_lidar, points);
  const bool converged_now = score_.add(t, step, truth, sim_.trajectory().onStairs(t));
  r_.error_series.back().true_storey = score_.trueStorey();
  r_.error_series.back().on_stairs = score_.onStairs();
  if (poses) poses->back().true_storey = score_.trueStorey(), poses->back().on_stairs = score_.onStairs();
  if (step.arrival && snapshot) snapshotNow("storey_change", t, truth, snapshot);
  if (converged_now) {
    if (step.filter) r_.convergence_margin = step.filter->filter.path_margin;
    if (snapshot) snapshotNow("convergence", t, truth, snapshot);
  }
}

ScenarioResult MethodRun::finish(double t_end, const Eigen::Isometry3d& truth_end, const SnapshotHook& snapshot) {
  const bim::Building& building = building_;
  const bool converged = score_.converged();
  if (!converged && last_verdict_) r_.hypotheses = pathPlaces(*last_verdict_, building.storeys[verdict_storey_]);
  if (localizer_->filter() && !localizer_->filter()->storey() && r_.storey_auto && last_bank_)
    for (const auto& c : last_bank_->candidates)
      r_.storey_candidates.push_back({building.storeyLabel(c.storey), c.converged, c.path_log_likelihood, c.path_best});
  // The last picture shows where the particles were left and why, or the graph the tracker built.
  if (snapshot && updates_ > 0 && (!converged || localizer_->tracker())) snapshotNow("end", t_end, truth_end, snapshot);
  score_.finish(r_);
  r_.map_rmse_m = map_error_.rmse_m();
  r_.site = scenario_.site.preset;
  if (const sgraph::SGraphTracker* tracker = localizer_->tracker()) scoreWalls(tracker->wallDeviations(), sim_.world().siteTruth(), r_);
  judge(scenario_, r_);
  return r_;
}

}  // namespace bimloc::sim
