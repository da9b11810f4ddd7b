// Scenarios run in parallel with results in input order (the same output whatever the number
// of jobs), worlds loaded once and shared: what `bimloc run` and `bimloc sweep` both do.
#pragma once

#include "sim/runner/run_scenario.hpp"

#include <functional>
#include <map>
#include <memory>
#include <mutex>
#include <string>
#include <vector>

namespace bimloc::cli {

// Worlds are loaded once and shared (read-only) by the scenarios that use them.
class WorldCache {
 public:
  const sim::World& get(const std::string& path);

 private:
  std::mutex mutex_;
  std::map<std::string, std::unique_ptr<sim::World>> worlds_;
};

struct RunPoolOptions {
  int jobs = 1;
  std::string snapshots;  // folder for snapshots, empty for none
  std::string trace;      // folder for trace CSVs, empty for none
  std::string tum;        // folder for truth.tum and estimate.tum per scenario, empty for none
  bool oracle = false;    // each run's information limit (sim/oracle/oracle.hpp), after the run
  std::string progress_label = "running";
};

// One scenario, checked against its world first. With `room_mode` (scenarios generated per
// start room, and the benchmark's), a plan whose doors are closed in the mesh has no path out
// of the room: the base walks inside it instead, and the result says so in a warning.
sim::ScenarioResult runChecked(const sim::Scenario& s, const sim::World& world, bool room_mode,
                               const sim::SnapshotHook& hook = {}, std::vector<sim::TraceRow>* trace = nullptr,
                               std::vector<sim::PoseRow>* poses = nullptr, bool with_oracle = false);

// The same for several methods on one simulation (sim::runScenarioMethods); snapshots[k],
// when given, takes method k's snapshots.
std::vector<sim::ScenarioResult> runCheckedMethods(const sim::Scenario& s, const sim::World& world, bool room_mode,
                                                   const std::vector<std::string>& methods,
                                                   const std::vector<sim::SnapshotHook>& snapshots = {});

// work(i) for every i in [0, count) on `jobs` threads (the caller's among them), with a
// progress bar on stderr labelled `progress_label`. `work` must not throw; each i writes its
// own slot of the caller's results, so they come out in input order whatever `jobs`.
void forEachInParallel(std::size_t count, int jobs, const std::string& progress_label,
                       const std::function<void(std::size_t)>& work);

struct PooledRun {
  sim::ScenarioResult result;
  std::string error;  // the scenario could not run at all
};

// What a user knows of the start, for every scenario: --prior-room NAME[,NAME...] and
// --prior-pose x,y,yaw_deg,sigma_m (the scenario's localizer.prior_* keys). Throws
// std::invalid_argument for a malformed pose.
// --config FILE.yaml: its localizer keys over every scenario's own (sections merged key by key).
void applyConfig(std::vector<sim::Scenario>& scenarios, const std::string& config_file);
void applyPrior(std::vector<sim::Scenario>& scenarios, const std::vector<std::string>& rooms, const std::string& pose);
// --motion: "tour" leaves every scenario's motion as it is (generated starts tour their rooms);
// "disambiguate" makes each base walk where its localizer suggests looking while it searches
// (motion.disambiguate), its script a tour (a scenario standing or wandering explores instead).
void applyMotion(std::vector<sim::Scenario>& scenarios, const std::string& motion);

// Keeps the scenarios whose start room is one of `rooms` (all when empty); throws naming an
// unknown room.
void keepStartRooms(std::vector<sim::Scenario>& scenarios, const std::vector<std::string>& rooms);

// `generated[i]`: scenario i was made from a plan (--all-rooms); when its tour finds no path
// out of the start room (doors closed in the mesh), it walks inside the room instead.
std::vector<PooledRun> runPool(const std::vector<sim::Scenario>& scenarios, const std::vector<bool>& generated,
                               WorldCache& worlds, const RunPoolOptions& options);

}  // namespace bimloc::cli
