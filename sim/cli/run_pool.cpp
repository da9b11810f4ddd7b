#include "sim/cli/run_pool.hpp"

#include "sim/cli/progress.hpp"
#include "sim/cli/snapshots.hpp"
#include "sim/cli/trace_writer.hpp"
#include "sim/runner/room_scenarios.hpp"

#include <algorithm>
#include <atomic>
#include <thread>

namespace bimloc::cli {

using namespace bimloc::sim;

const World& WorldCache::get(const std::string& path) {
  std::lock_guard<std::mutex> lock(mutex_);
  auto it = worlds_.find(path);
  if (it == worlds_.end()) it = worlds_.emplace(path, std::make_unique<World>(World::load(path))).first;
  return *it->second;
}

ScenarioResult runChecked(const Scenario& s, const World& world, bool room_mode, const SnapshotHook& hook,
                          std::vector<TraceRow>* trace, std::vector<PoseRow>* poses) {
  try {
    checkScenarioAgainstWorld(s, world);
    return runScenario(s, world, hook, trace, poses);
  } catch (const ScenarioError& e) {
    if (!room_mode) throw;
    if (trace) trace->clear();
    if (poses) poses->clear();
    ScenarioResult r = runScenario(stayInRoom(s), world, hook, trace, poses);
    r.warnings.insert(r.warnings.begin(), std::string("no path out of the room, walked inside it: ") + e.what());
    return r;
  }
}

namespace {

ScenarioResult runOne(const Scenario& s, WorldCache& worlds, const RunPoolOptions& options, bool room_mode) {
  const World& world = worlds.get(s.world);
  const SnapshotHook hook = options.snapshots.empty() ? SnapshotHook{} : snapshotWriter(world, s, options.snapshots);
  std::vector<TraceRow> rows;
  std::vector<TraceRow>* trace = options.trace.empty() ? nullptr : &rows;
  std::vector<PoseRow> pose_rows;
  std::vector<PoseRow>* poses = options.tum.empty() ? nullptr : &pose_rows;
  const auto traced = [&](ScenarioResult r) {
    if (trace) writeTrace(options.trace, s.name, rows);
    if (poses) writeTumPair(options.tum, s.name, pose_rows);
    if (!options.snapshots.empty()) writeErrorPlot(options.snapshots, s.name, r);  // next to the snapshots
    return r;
  };
  return traced(runChecked(s, world, room_mode, hook, trace, poses));
}

}  // namespace

void applyPrior(std::vector<Scenario>& scenarios, const std::vector<std::string>& rooms, const std::string& pose) {
  std::vector<double> v;
  if (!pose.empty()) {
    std::size_t at = 0;
    while (at <= pose.size()) {
      const std::size_t comma = std::min(pose.find(',', at), pose.size());
      try {
        std::size_t used = 0;
        v.push_back(std::stod(pose.substr(at, comma - at), &used));
        if (used != comma - at) throw std::invalid_argument("");
      } catch (const std::exception&) {
        throw std::invalid_argument("--prior-pose '" + pose + "': expected x,y,yaw_deg,sigma_m");
      }
      at = comma + 1;
    }
    if (v.size() != 4 || !(v[3] > 0)) throw std::invalid_argument("--prior-pose '" + pose + "': expected x,y,yaw_deg,sigma_m");
  }
  for (auto& s : scenarios) {
    if (!rooms.empty()) s.localizer["prior_rooms"] = rooms;
    if (!v.empty()) s.localizer["prior_pose"] = {v[0], v[1], v[2]}, s.localizer["prior_sigma_m"] = v[3];
  }
}

void applyConfig(std::vector<Scenario>& scenarios, const std::string& config_file) {
  const nlohmann::json block = loadLocalizerBlock(config_file);
  for (auto& s : scenarios) s.localizer.merge_patch(block);
}

void keepStartRooms(std::vector<Scenario>& scenarios, const std::vector<std::string>& rooms) {
  if (rooms.empty()) return;
  std::vector<Scenario> kept;
  for (const auto& name : rooms) {
    bool found = false;
    for (const auto& s : scenarios)
      if (s.start.room == name) kept.push_back(s), found = true;
    if (!found) throw std::invalid_argument("--rooms: no start room '" + name + "' on this storey");
  }
  scenarios = std::move(kept);
}

std::vector<PooledRun> runPool(const std::vector<Scenario>& scenarios, const std::vector<bool>& generated, WorldCache& worlds,
                               const RunPoolOptions& options) {
  std::vector<PooledRun> runs(scenarios.size());
  std::atomic<std::size_t> next{0}, done{0};
  Progress progress(options.progress_label);
  std::mutex progress_mutex;
  const auto work = [&] {
    for (std::size_t i = next++; i < scenarios.size(); i = next++) {
      try {
        runs[i].result = runOne(scenarios[i], worlds, options, i < generated.size() && generated[i]);
      } catch (const std::exception& e) {
        runs[i].error = e.what();
        runs[i].result.name = scenarios[i].name;
        runs[i].result.failures.push_back(e.what());
      }
      std::lock_guard<std::mutex> lock(progress_mutex);
      progress.update(++done, scenarios.size());
    }
  };
  std::vector<std::thread> pool;
  for (int j = 1; j < std::min<int>(options.jobs, static_cast<int>(scenarios.size())); ++j) pool.emplace_back(work);
  work();
  for (auto& t : pool) t.join();
  return runs;
}

}  // namespace bimloc::cli
