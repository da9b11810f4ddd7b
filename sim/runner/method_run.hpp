// One localizer stepped through a simulated run and scored: what the runner keeps per method,
// so that one simulation (the same scans, the same odometry, bit for bit) can feed several
// localizers turn by turn (`bimloc compare`), `bimloc run` being the case of one.
#pragma once

#include "sim/metrics/map_error.hpp"
#include "sim/runner/evaluation.hpp"
#include "sim/runner/run_scenario.hpp"
#include "sim/simulation/simulator.hpp"

#include <optional>
#include <random>
#include <vector>

namespace bimloc::sim {

class MethodRun {
 public:
  // `plan`: the world the localizer is given (the simulator's own may be a site built from it).
  // `shared`: the run's fields every method has in common (name, plan, seed, rooms, storey).
  // Throws ScenarioError naming the scenario's file when the localizer refuses its settings.
  MethodRun(const Scenario& scenario, const World& plan, const Simulator& sim, const LocalizerSettings& settings,
            const ScenarioResult& shared);

  // One turn: its mid-turn time t, the odometry then, its points (read only when used) and
  // the truth at t. `snapshot`, `trace` and `poses` as runScenario's (empty / null for none).
  void step(double t, const Eigen::Isometry3d& T_odom_base, const Localizer::PointSource& points,
            const Eigen::Isometry3d& truth, const SnapshotHook& snapshot, std::vector<TraceRow>* trace,
            std::vector<PoseRow>* poses = nullptr);

  // Whether the localizer is still searching (not converged) after its last step; true before.
  bool searching() const { return searching_; }
  // The last step's state and suggested goal: what a steered base follows (GuidedWalk).
  LocalizationState lastState() const { return last_state_; }
  const std::optional<guide::LookGoal>& lastGoal() const { return last_goal_; }
  std::size_t lastPlaces() const { return last_places_; }  // LocalizationResult::places' count

  // The snapshot of `phase` now (initialization before the first step).
  void snapshotNow(const char* phase, double t, const Eigen::Isometry3d& truth, const SnapshotHook& snapshot) const;

  // The scores from the last step, and the last snapshot (when the run ended at t_end).
  ScenarioResult finish(double t_end, const Eigen::Isometry3d& truth_end, const SnapshotHook& snapshot);

 private:
  const Scenario& scenario_;
  const bim::Building& building_;
  const Simulator& sim_;
  ScenarioResult r_;
  std::optional<Localizer> localizer_;
  std::optional<Barometer> barometer_;  // with `--altitude`
  RunScore score_;
  MapErrorSampler map_error_;
  LocalizationState last_state_ = LocalizationState::Searching;
  std::optional<guide::LookGoal> last_goal_;
  std::size_t last_places_ = 0;
  std::optional<Eigen::Isometry3d> estimate_;    // the last step's, for the snapshots
  std::optional<std::size_t> storey_;            // ... and its storey
  std::optional<pf::UpdateReport> last_verdict_;  // the last update the path evidence spoke at
  std::size_t verdict_storey_ = 0;                // ... and the storey it spoke of
  std::optional<pf::StoreyBankReport> last_bank_;
  int updates_ = 0;
  bool searching_ = true;
};

}  // namespace bimloc::sim
