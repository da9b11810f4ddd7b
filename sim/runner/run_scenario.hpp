// Runs one scenario in the loop: the simulator feeds scans and odometry, at the sensor's rate,
// into the same localizer library that runs on recorded data, and the result is scored
// against the ground truth and the scenario's expectations.
#pragma once

#include "sim/dataset/recording_checks.hpp"
#include "sim/oracle/oracle.hpp"
#include "sim/scenario/localizer_config.hpp"
#include "sim/scenario/scenario.hpp"
#include "sim/world/world.hpp"

#include <bimloc/localizer.hpp>

#include <functional>
#include <optional>
#include <string>
#include <vector>

namespace bimloc::sim {

// The scenario's `localizer:` mapping over the defaults (sim/scenario/localizer_config.hpp),
// seeded from the scenario's seed; its storey is the runner's to set. Throws ScenarioError at
// FILE:LINE for an unknown key or a bad value.
LocalizerSettings localizerSettings(const Scenario& scenario);

// How the localizer is told storey `index`: its GlobalId when that is unique, else the index.
std::string storeyKey(const bim::Building& building, std::size_t index);

struct ScenarioResult {
  // storey: where the simulator ran (the truth). start_room: the start's room, "(pose)", or for
  // an outside_rooms start where it was: "(doorway)", "(no room)", "(outside)".
  std::string name, plan, storey, start_room, method;
  bool storey_auto = false;                 // the localizer was not told the storey
  std::optional<std::string> found_storey;  // the storey it converged on (a wrong one is a false convergence)
  // With storey auto: the path evidence's margin of the decided storey's place over every
  // other storey's best place (per distinct face) when it was decided.
  std::optional<double> storey_margin;
  // With storey auto and no storey decided: the storeys still considered, leader first, with
  // whether their filter converged and the path's log-likelihood at their best place.
  struct StoreyOption {
    std::string storey;
    bool converged = false;
    double path_log_likelihood = 0;
    std::optional<Eigen::Vector3d> best;  // its path evidence's best place (map x, y, yaw in rad)
  };
  std::vector<StoreyOption> storey_candidates;
  std::uint64_t seed = 0;
  bool converged = false;
  std::optional<double> convergence_time_s;
  std::optional<std::string> found_room;  // room of the estimate at convergence
  std::string true_room;                  // room of the truth at convergence (or at the end)
  double position_error_m = 0;            // at the end of the run
  double yaw_error_deg = 0;
  std::optional<double> ate_m;            // RMSE of position after convergence, no alignment
  // RPE: RMSE of the relative translation error over every stretch of 1 m of true path after
  // convergence (m per metre travelled); unset when the robot walked less than that.
  std::optional<double> rpe_m_per_m;
  int losses = 0;                         // losses of track after convergence
  // Changes of the true storey (the base climbed a flight onto another floor), and how many of
  // them the localizer followed: on the new storey within 5 s of the base leaving the flight.
  int storey_changes = 0, storey_changes_followed = 0;
  // Changes the base made before the localizer's first convergence (it tracked no storey yet):
  // not in storey_changes, nothing to follow.
  int storey_changes_searching = 0;
  // Of each change followed, the time from the base leaving the flight (standing on the new
  // floor) to the first step the localizer was on the new storey: 0 when it was there first.
  std::vector<double> storey_follow_lags_s;
  // The scans after convergence (one a second, every 20th point), placed with the estimate,
  // against the plan's storey mesh: the paper's "point cloud RMSE", no ground truth needed.
  std::optional<double> map_rmse_m;
  // The S-Graph's estimate of each plan wall it observed (its offset from the plan position),
  // with the site's truth for that wall when the world is a site (`site:`).
  struct WallEstimate {
    sgraph::WallDeviation estimate;
    std::optional<double> true_offset_m, true_angle_deg;
  };
  std::vector<WallEstimate> wall_deviations;
  std::string site = "exact";  // the site preset (or "custom")
  // Largest |estimated - true| offset over the walls the site shifted and the S-Graph saw at
  // least kWellSeen times (a wall seen once or twice is barely estimated).
  std::optional<double> wall_offset_error_m;
  bool false_convergence = false;         // converged while > 0.5 m or > 10 deg off, at any time after
  // The path evidence's margin at the update that declared convergence (per distinct face).
  std::optional<double> convergence_margin;
  // The path verdicts the evidence's fitting loop left under the bar while the lowest rival's
  // full margin, fitted, was at or above it (UpdateReport::path_bound_held: a lower bound or an
  // unfitted rival held them before session 29), the reverse (path_fit_lowered), and the time
  // of the first of each.
  int verdicts_bound_held = 0, verdicts_fit_lowered = 0;
  std::optional<double> first_bound_held_s, first_fit_lowered_s;
  // Not converged: the distinct places the path still fits (best first), each with the room
  // it is in and its weight relative to the others (exp of minus the margin, normalised).
  struct Place {
    double x = 0, y = 0, yaw_deg = 0, relative_weight = 0;
    std::string room, storey;
  };
  std::vector<Place> hypotheses;
  bool passed = false;
  std::vector<std::string> failures;      // why it did not pass
  std::vector<std::string> warnings;
  // A recording's run (`bimloc localize`): what its readers dropped and why; unset for
  // simulated runs, whose input is the simulator's own.
  std::optional<RecordingChecks> recording;
  double sim_seconds = 0, wall_seconds = 0;
  // Of wall_seconds, the simulator's setup before the first turn: the base's tour planned
  // through the storey (A* on a 5 cm grid of body sweeps) and the odometry drawn. It grows
  // with the building and the tour, and is not the loop.
  double setup_seconds = 0;
  double path_length_m = 0;  // the robot's true path in the plane
  // A guided walk's (motion disambiguate) use of the localizer's goals, while searching: the
  // steps with two or more places, the steps with a goal suggested, the goals the base took up,
  // and when the first goal was suggested. Unset for a tour (its localizer plans no goal).
  struct GuideUse {
    int place_steps = 0, goal_steps = 0, goals_taken = 0;
    std::optional<double> first_goal_s;
  };
  std::optional<GuideUse> guide;
  // The error of the localizer's estimate at every step (for plots; not in the JSON).
  struct ErrorSample {
    double time_s = 0, position_m = 0, yaw_deg = 0;
    LocalizationState state = LocalizationState::Searching;
    // The truth's storey at this step (index into the plan's storeys; RunScore::trueStorey: on
    // a flight, the one the base came from until it steps off) and whether the base is on a
    // flight (issue 31).
    std::size_t true_storey = 0;
    bool on_stairs = false;
    std::optional<std::size_t> storey;  // the localizer's (LocalizationResult::storey)
  };
  std::vector<ErrorSample> error_series;
  // Wall seconds the localizer's steps took in each simulated minute (the last one partial).
  std::vector<double> localizer_seconds_by_minute;
  // The whole loop's CPU seconds (the process's: simulator, planes, localizer, scoring) per
  // turn, split by what the first localizer was doing when the turn began: searching (not yet
  // converged) or tracking; and the simulated seconds of those turns. The setup before the
  // first turn is in neither. Real-time factors per phase: bench loop.
  double search_cpu_seconds = 0, search_sim_seconds = 0, tracking_cpu_seconds = 0, tracking_sim_seconds = 0;
  // With the oracle (`--oracle`): when the scans first ruled out every place but the true one
  // (sim/oracle/oracle.hpp), from the run's own scans, odometry and truth. Not in wall_seconds.
  std::optional<oracle::OracleVerdict> oracle;
};

// What a snapshot needs at a moment of the run (the runner calls it at initialization, while
// the particles cluster, and at convergence).
struct SnapshotMoment {
  std::string phase;  // initialization | clustering | convergence | storey_change | end (not converged)
  double time_s = 0;
  const pf::ParticleFilter* filter = nullptr;  // the leading storey's, with storey auto
  std::size_t storey = 0;                      // the filter's storey
  Eigen::Isometry3d truth = Eigen::Isometry3d::Identity();
  const sgraph::SGraphTracker* tracker = nullptr;  // once the S-Graph tracks: its graph
  // The localizer's estimate at its last step (unset before the first): once the S-Graph
  // tracks, the filter stops and its own estimate goes stale.
  std::optional<Eigen::Isometry3d> estimate;
};
using SnapshotHook = std::function<void(const SnapshotMoment&)>;

// One weighing of the filter, for `bimloc run --trace`: what the filter believed, what the
// path evidence said, and the truth, to see why a run converged when it did, or never.
struct TraceRow {
  double time_s = 0;
  Eigen::Vector3d truth = Eigen::Vector3d::Zero();     // map x, y, yaw
  Eigen::Vector3d estimate = Eigen::Vector3d::Zero();  // the filter's map <- base
  pf::UpdateReport report;          // of the leading storey's filter
  std::string storey;               // with storey auto: the leading (or decided) storey; else empty
  std::optional<double> storey_margin;  // StoreyBankReport::storey_margin
  // The localizer's places (LocalizationResult::places) and its goal, if any (motion disambiguate).
  std::size_t places = 0;
  std::optional<guide::LookGoal> goal;
};

// One localizer step, for `bimloc run --tum`: the true and the estimated map <- base, and
// whether the ATE scores the step (RunScore::scored).
struct PoseRow {
  double time_s = 0;
  Eigen::Isometry3d truth = Eigen::Isometry3d::Identity(), estimate = Eigen::Isometry3d::Identity();
  bool scored = false;
  std::size_t true_storey = 0;  // as ScenarioResult::ErrorSample's
  bool on_stairs = false;
};

// `trace`, when given, receives a row per weighing; `poses` a row per step. With `with_oracle`,
// the oracle keeps the run's keyframes and gives its verdict at the end (ScenarioResult::oracle).
ScenarioResult runScenario(const Scenario& scenario, const World& world, const SnapshotHook& snapshot = {},
                           std::vector<TraceRow>* trace = nullptr, std::vector<PoseRow>* poses = nullptr,
                           bool with_oracle = false);

// Several localizers on one simulation, each stepped on every turn before the next turn is
// made: each method gets the same scans and the same odometry, bit for bit, and its own
// score by the same rule (RunScore). `methods` ("sgraph", "pf", "pf-no-rooms", "amcl", "ndt")
// each replace the scenario's `localizer.method`; result k is what runScenario gives for the
// scenario with method k (only wall_seconds, which counts every method, differs).
// snapshots[k], when given and set, takes method k's snapshots, as runScenario's hook does.
std::vector<ScenarioResult> runScenarioMethods(const Scenario& scenario, const World& world,
                                               const std::vector<std::string>& methods,
                                               const std::vector<SnapshotHook>& snapshots = {});

// CPU seconds of the process (all its threads): on a shared machine wall time also counts
// waiting for a core (bench loop's and bench bags' CPU columns).
double processCpuSeconds();

}  // namespace bimloc::sim
