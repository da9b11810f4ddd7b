#include "sim/runner/localize_recording.hpp"

#include "sim/dataset/deskew.hpp"
#include "sim/metrics/map_error.hpp"
#include "sim/runner/evaluation.hpp"
#include "sim/runner/path_places.hpp"

#include <chrono>
#include <memory>

namespace bimloc::sim {

RecordingRun localizeRecording(const bim::Building& building, std::size_t truth_storey, Localizer& localizer,
                               const Eigen::Isometry3d& T_base_lidar, const TurnSource& turns, double start_s,
                               const std::vector<StampedPose>& truth, ScenarioResult result,
                               const TurnObserver& observe) {
  const auto start = std::chrono::steady_clock::now();
  RecordingRun run;
  ScenarioResult& r = run.result;
  r = std::move(result);
  RunScore score(building, truth_storey);
  MapErrorSampler map_error(building);  // the scans placed with the estimate against the plan's mesh
  std::optional<double> first_stamp, last_stamp, period;
  // The last update the path evidence spoke at, and its storey: the places left when the run
  // ends unconverged (as `bimloc run` reports them).
  std::optional<pf::UpdateReport> last_verdict;
  std::size_t verdict_storey = truth_storey;
  RecordingChecks checks;
  turns([&](const RecordedTurn& turn) {
    ++checks.scans;
    checks.points += turn.drops;
    for (const auto& w : turn.warnings) ++checks.layout_warnings[w];
    if (turn.drops.read == turn.drops.dropped()) {
      if (++checks.scans_skipped <= 3) checks.skipped_names.push_back(turn.name);
      return;
    }
    // The localizer and the map error may both want the points: read (decode, de-skew) once.
    auto cache = std::make_shared<std::optional<std::vector<Eigen::Vector3f>>>();
    const Localizer::PointSource points = [&turn, cache]() -> std::vector<Eigen::Vector3f> {
      if (!*cache) *cache = turn.points();
      return **cache;
    };
    auto& last = run.last;
    last = localizer.step(turn.stamp_s, turn.T_odom_base, points);
    if (last->filter && last->filter->decided && !r.storey_margin && r.storey_auto) r.storey_margin = last->filter->storey_margin;
    for (const auto& w : last->warnings) r.warnings.push_back(turn.name + ": " + w);
    if (last->filter && last->filter->filter.path_best && last->filter->filter.places_fitted) last_verdict = last->filter->filter, verdict_storey = last->filter->leader;
    map_error.step(*last, T_base_lidar, points);
    if (!first_stamp) first_stamp = turn.stamp_s;
    if (last_stamp && !period) period = turn.stamp_s - *last_stamp;
    last_stamp = turn.stamp_s;
    if (!truth.empty()) {
      // Interpolated at the turn's stamp: the truth's samples (50 Hz) straddle the mid-turn
      // stamps, and the nearest one is 10 ms off, a few millimetres of ATE on a walking robot.
      const Eigen::Isometry3d T = interpolatePose(truth, turn.stamp_s);
      const double t = turn.stamp_s - start_s;
      score.add(t, *last, T);
      r.error_series.push_back({t, (last->T_map_base.translation() - T.translation()).head<2>().norm(),
                                yawErrorDeg(last->T_map_base, T), last->state, score.trueStorey(), score.onStairs(), last->storey});
    }
    if (observe) observe(turn, *last);
  });
  if (checks.scans > 0 && checks.scans_skipped == checks.scans) {
    std::vector<std::string> why = checks.warnings();
    throw std::runtime_error(r.name + ": no scan has a usable point: " + why.front() + (why.size() > 1 ? "; " + why[1] : ""));
  }
  r.recording = checks;
  const auto& last = run.last;
  if (truth.empty()) {
    r.converged = last && last->convergence_stamp_s;
    if (last && last->storey) r.found_storey = building.storeyLabel(*last->storey);
    r.losses = last ? last->losses : 0;
  } else {
    score.finish(r);
  }
  if (!r.converged && last_verdict) r.hypotheses = pathPlaces(*last_verdict, building.storeys[verdict_storey]);
  if (const auto* tracker = localizer.tracker())
    for (const auto& w : tracker->wallDeviations()) r.wall_deviations.push_back({w, std::nullopt, std::nullopt});
  r.map_rmse_m = map_error.rmse_m();
  // The recording's span, a turn included (the first turn's stamp is its middle).
  r.sim_seconds = first_stamp ? *last_stamp - *first_stamp + period.value_or(0.0) : 0.0;
  r.wall_seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  r.passed = r.converged && !r.false_convergence;
  return run;
}

}  // namespace bimloc::sim
