// bimloc run SCENARIO... | --plan PLAN --all-rooms  [--json] [--out DIR] [--jobs N]
#include "sim/cli/commands.hpp"
#include "sim/cli/progress.hpp"
#include "sim/cli/run_report.hpp"
#include "sim/cli/snapshots.hpp"
#include "sim/cli/trace_writer.hpp"
#include "sim/runner/room_scenarios.hpp"
#include "sim/runner/run_scenario.hpp"

#include <atomic>
#include <chrono>
#include <iostream>
#include <map>
#include <mutex>
#include <thread>

namespace {

using namespace bimloc::sim;

struct RunArgs {
  std::vector<std::string> scenarios;
  std::string plan;
  std::string storey = "0";
  bool all_rooms = false;
  int seeds = 1;
  std::string method = "pf";
  double duration_s = 40.0;
  bool json = false;
  std::string out;
  std::string trace;
  int jobs = 1;
};

// Worlds are loaded once and shared (read-only) by the scenarios that use them.
class WorldCache {
 public:
  const World& get(const std::string& path) {
    std::lock_guard<std::mutex> lock(mutex_);
    auto it = worlds_.find(path);
    if (it == worlds_.end()) it = worlds_.emplace(path, std::make_unique<World>(World::load(path))).first;
    return *it->second;
  }

 private:
  std::mutex mutex_;
  std::map<std::string, std::unique_ptr<World>> worlds_;
};

ScenarioResult runOne(const Scenario& s, WorldCache& worlds, const RunArgs& args, bool room_mode) {
  const World& world = worlds.get(s.world);
  const SnapshotHook hook = args.out.empty() ? SnapshotHook{} : bimloc::cli::snapshotWriter(world, s, args.out);
  std::vector<TraceRow> rows;
  std::vector<TraceRow>* trace = args.trace.empty() ? nullptr : &rows;
  const auto traced = [&](ScenarioResult r) {
    if (trace) bimloc::cli::writeTrace(args.trace, s.name, rows);
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

void run(const RunArgs& args) {
  std::vector<Scenario> scenarios;
  WorldCache worlds;
  for (const auto& path : args.scenarios) scenarios.push_back(loadScenario(path));
  if (args.all_rooms) {
    if (args.plan.empty()) throw std::runtime_error("--all-rooms needs --plan PLAN");
    RoomScenarioOptions o;
    o.plan = args.plan, o.storey = args.storey, o.seeds = args.seeds, o.method = args.method, o.duration_s = args.duration_s;
    const auto generated = roomScenarios(worlds.get(args.plan), o);
    scenarios.insert(scenarios.end(), generated.begin(), generated.end());
  }
  if (scenarios.empty()) throw std::runtime_error("nothing to run: give scenario files, or --plan PLAN --all-rooms");

  // Scenarios in parallel, results in input order: the same output whatever --jobs.
  const auto start = std::chrono::steady_clock::now();
  std::vector<ScenarioResult> results(scenarios.size());
  std::vector<std::string> errors(scenarios.size());
  std::atomic<std::size_t> next{0}, done{0};
  bimloc::cli::Progress progress("running");
  std::mutex progress_mutex;
  const auto work = [&] {
    for (std::size_t i = next++; i < scenarios.size(); i = next++) {
      try {
        results[i] = runOne(scenarios[i], worlds, args, args.all_rooms && i >= args.scenarios.size());
      } catch (const std::exception& e) {
        errors[i] = e.what();
        results[i].name = scenarios[i].name;
        results[i].failures.push_back(e.what());
      }
      std::lock_guard<std::mutex> lock(progress_mutex);
      progress.update(++done, scenarios.size());
    }
  };
  std::vector<std::thread> pool;
  for (int j = 1; j < std::min<int>(args.jobs, static_cast<int>(scenarios.size())); ++j) pool.emplace_back(work);
  work();
  for (auto& t : pool) t.join();
  const double wall = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();

  const auto report = bimloc::cli::runReport(results, wall);
  if (args.json)
    std::cout << report.dump() << "\n";
  else
    bimloc::cli::printRunTable(results, report, std::cout);
  for (std::size_t i = 0; i < errors.size(); ++i)
    if (!errors[i].empty()) std::cerr << "bimloc run: error: " << errors[i] << "\n";
  bool all_passed = true;
  for (const auto& r : results) all_passed = all_passed && r.passed;
  if (!all_passed) throw bimloc::cli::ExitCode{1};
}

}  // namespace

void addRunCommand(CLI::App& app) {
  auto args = std::make_shared<RunArgs>();
  CLI::App* cmd = app.add_subcommand(
      "run",
      "Run scenarios in the loop: the simulator feeds scans and odometry at the sensor's rate into the localizer\n"
      "(the room-aware particle filter), and each run is scored against the ground truth and the scenario's\n"
      "expectations: converged, convergence time, room found, errors, ATE, false convergence. Exit status 1\n"
      "when any scenario fails. With --plan PLAN --all-rooms: one scenario per room of the storey.");
  cmd->add_option("scenarios", args->scenarios, "scenario files (YAML)");
  cmd->add_option("--plan", args->plan, "IFC plan (or extract folder) for --all-rooms");
  cmd->add_option("--storey", args->storey, "storey name or index for --all-rooms")->capture_default_str();
  cmd->add_flag("--all-rooms", args->all_rooms, "one scenario per room of the storey: random start in it, walk out");
  cmd->add_option("--seeds", args->seeds, "seeds per room with --all-rooms")->check(CLI::Range(1, 1000))->capture_default_str();
  cmd->add_option("--method", args->method, "pf (with the room factor) or pf-no-rooms (the ablation)")
      ->check(CLI::IsMember({"pf", "pf-no-rooms"}))
      ->capture_default_str();
  cmd->add_option("--duration", args->duration_s, "seconds per --all-rooms scenario")->check(CLI::Range(1.0, 3600.0));
  cmd->add_flag("--json", args->json, "print one JSON object instead of the table");
  cmd->add_option("--out", args->out, "folder for top-view PNG snapshots (initialization, clustering, convergence)");
  cmd->add_option("--trace", args->trace,
                  "folder for one CSV per scenario: a row per weighing (truth, estimate, the path evidence's best "
                  "place and margin)");
  cmd->add_option("--jobs", args->jobs, "scenarios run in parallel")->check(CLI::Range(1, 256))->capture_default_str();
  cmd->callback([args] { run(*args); });
}
