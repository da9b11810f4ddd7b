// Runs one scenario in the loop: the simulator feeds scans and odometry, at the sensor's rate,
// into the same localizer library that runs on recorded data, and the result is scored
// against the ground truth and the scenario's expectations.
#pragma once

#include "sim/scenario/scenario.hpp"
#include "sim/world/world.hpp"

#include <bimloc/pf/particle_filter.hpp>
#include <bimloc/pf/storey_bank.hpp>
#include <bimloc/planes/plane_extraction.hpp>

#include <functional>
#include <optional>
#include <string>
#include <vector>

namespace bimloc::sim {

struct LocalizerSettings {
  pf::ParticleFilterConfig filter;
  planes::PlaneExtractionConfig planes;
  bool storey_auto = false;  // localizer.storey: auto (the scenario's `storey: auto` sets it)
};

// The scenario's `localizer:` mapping over the defaults (method: pf | pf-no-rooms, particles,
// ...). Throws ScenarioError naming the file for an unknown key or a bad value.
LocalizerSettings localizerSettings(const Scenario& scenario);

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
  bool false_convergence = false;         // converged while > 0.5 m or > 10 deg off, at any time after
  // The path evidence's margin at the update that declared convergence (per distinct face).
  std::optional<double> convergence_margin;
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
  double sim_seconds = 0, wall_seconds = 0;
};

// What a snapshot needs at a moment of the run (the runner calls it at initialization, while
// the particles cluster, and at convergence).
struct SnapshotMoment {
  std::string phase;  // initialization | clustering | convergence | end (not converged)
  double time_s = 0;
  const pf::ParticleFilter* filter = nullptr;  // the leading storey's, with storey auto
  std::size_t storey = 0;                      // the filter's storey
  Eigen::Isometry3d truth = Eigen::Isometry3d::Identity();
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
};

// `trace`, when given, receives a row per weighing.
ScenarioResult runScenario(const Scenario& scenario, const World& world, const SnapshotHook& snapshot = {},
                           std::vector<TraceRow>* trace = nullptr);

}  // namespace bimloc::sim
