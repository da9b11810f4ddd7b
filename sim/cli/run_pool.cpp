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

namespace {

ScenarioResult runOne(const Scenario& s, WorldCache& worlds, const RunPoolOptions& options, bool room_mode) {
  const World& world = worlds.get(s.world);
  const SnapshotHook hook = options.snapshots.empty() ? SnapshotHook{} : snapshotWriter(world, s, options.snapshots);
  std::vector<TraceRow> rows;
  std::vector<TraceRow>* trace = options.trace.empty() ? nullptr : &rows;
  const auto traced = [&](ScenarioResult r) {
    if (trace) writeTrace(options.trace, s.name, rows);
    return r;
  };
  try {
    checkScenarioAgainstWorld(s, world);
    return traced(runScenario(s, world, hook, trace));
  } catch (const ScenarioError& e) {
    // A plan whose doors are closed in the mesh has no path out of the room: walk in it.
    if (room_mode) {
      rows.clear();
      ScenarioResult r = traced(runScenario(stayInRoom(s), world, hook, trace));
      r.warnings.insert(r.warnings.begin(), std::string("no path out of the room, walked inside it: ") + e.what());
      return r;
    }
    throw;
  }
}

}  // namespace

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
