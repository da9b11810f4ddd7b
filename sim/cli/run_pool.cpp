#include "sim/cli/run_pool.hpp"

#include "sim/cli/progress.hpp"
#include "sim/cli/snapshots.hpp"
#include "sim/cli/trace_writer.hpp"
#include "sim/runner/room_scenarios.hpp"

#include <algorithm>
#include <atomic>
#include <functional>
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

void addWarning(ScenarioResult& r, const std::string& w) { r.warnings.insert(r.warnings.begin(), w); }
void addWarning(std::vector<ScenarioResult>& rs, const std::string& w) {
  for (auto& r : rs) addWarning(r, w);
}

// `run` on the scenario checked against its world, or in room mode, when that finds no path
// out of the start room, on the same scenario walking inside it.
template <typename Run>
auto checked(const Scenario& s, const World& world, bool room_mode, std::vector<TraceRow>* trace, const Run& run) {
  try {
    checkScenarioAgainstWorld(s, world);
    return run(s);
  } catch (const ScenarioError& e) {
    if (!room_mode) throw;
    if (trace) trace->clear();
    auto r = run(stayInRoom(s));
    addWarning(r, std::string("no path out of the room, walked inside it: ") + e.what());
    return r;
  }
}

}  // namespace

ScenarioResult runChecked(const Scenario& s, const World& world, bool room_mode, const SnapshotHook& hook,
                          std::vector<TraceRow>* trace, std::vector<PoseRow>* poses, bool with_oracle) {
  return checked(s, world, room_mode, trace, [&](const Scenario& one) {
    if (poses) poses->clear();  // the second try, walking inside the room, starts afresh
    return runScenario(one, world, hook, trace, poses, with_oracle);
  });
}

std::vector<ScenarioResult> runCheckedMethods(const Scenario& s, const World& world, bool room_mode,
                                              const std::vector<std::string>& methods, const std::vector<SnapshotHook>& snapshots) {
  return checked(s, world, room_mode, nullptr,
                 [&](const Scenario& one) { return runScenarioMethods(one, world, methods, snapshots); });
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
  return traced(runChecked(s, world, room_mode, hook, trace, poses, options.oracle));
}

}  // namespace

void applyMotion(std::vector<Scenario>& scenarios, const std::string& motion) {
  if (motion == "tour") return;
  if (motion != "disambiguate") throw std::invalid_argument("--motion must be tour or disambiguate, got '" + motion + "'");
  for (auto& s : scenarios) {
    s.motion.disambiguate = true;
    if (s.motion.kind != sim::MotionConfig::Kind::Tour) s.motion.kind = sim::MotionConfig::Kind::Tour, s.motion.rooms.clear();
    s.motion.skip_unreachable_rooms = s.motion.explore_after_tour = true;
  }
}

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
    if (!found) {
      // Name the plan and what it has: a room the extraction skipped (damaged geometry) is in
      // its warnings, and a typo is seen in the list.
      std::string have;
      for (std::size_t k = 0; k < scenarios.size() && k < 12; ++k) have += (k ? ", " : "") + scenarios[k].start.room;
      if (scenarios.size() > 12) have += ", ...";
      const std::string plan = scenarios.empty() ? std::string("the plan") : scenarios.front().world;
      throw std::invalid_argument("--rooms: " + plan + " has no start room '" + name + "' on this storey (its rooms: " +
                                  (have.empty() ? std::string("none") : have) + "; `bimloc extract` names any it skipped)");
    }
  }
  scenarios = std::move(kept);
}

void forEachInParallel(std::size_t count, int jobs, const std::string& progress_label,
                       const std::function<void(std::size_t)>& work) {
  std::atomic<std::size_t> next{0}, done{0};
  Progress progress(progress_label);
  std::mutex progress_mutex;
  const auto worker = [&] {
    for (std::size_t i = next++; i < count; i = next++) {
      work(i);
      std::lock_guard<std::mutex> lock(progress_mutex);
      progress.update(++done, count);
    }
  };
  std::vector<std::thread> pool;
  for (int j = 1; j < std::min<int>(jobs, static_cast<int>(count)); ++j) pool.emplace_back(worker);
  worker();
  for (auto& t : pool) t.join();
}

std::vector<PooledRun> runPool(const std::vector<Scenario>& scenarios, const std::vector<bool>& generated, WorldCache& worlds,
                               const RunPoolOptions& options) {
  std::vector<PooledRun> runs(scenarios.size());
  forEachInParallel(scenarios.size(), options.jobs, options.progress_label, [&](std::size_t i) {
    try {
      runs[i].result = runOne(scenarios[i], worlds, options, i < generated.size() && generated[i]);
    } catch (const std::exception& e) {
      runs[i].error = e.what();
      runs[i].result.name = scenarios[i].name;
      runs[i].result.failures.push_back(e.what());
    }
  });
  return runs;
}

}  // namespace bimloc::cli
