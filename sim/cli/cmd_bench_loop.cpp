// bimloc bench loop [SCENARIO...] [--plan P --storey S] [--multi-storey] [--altitude] [--rounds N] [--json]
// The whole loop on one core: simulator and localizer (plane extraction, particle filter, path
// evidence) as `bimloc run --jobs 1` runs them, against the simulator alone on the same
// scenario in the same run. Real-time factors, and the localizer's share of the loop; the
// simulator's setup (tour planning) in a column of its own, outside both factors.
#include "sim/cli/commands.hpp"
#include "sim/cli/run_pool.hpp"
#include "sim/cli/table.hpp"
#include "sim/runner/room_scenarios.hpp"
#include "sim/runner/run_scenario.hpp"
#include "sim/simulation/simulator.hpp"

#include <algorithm>
#include <chrono>
#include <filesystem>
#include <iostream>
#include <numeric>

namespace {

using namespace bimloc::sim;
using Clock = std::chrono::steady_clock;

struct LoopBenchArgs {
  std::vector<std::string> scenarios{"scenarios/site_office/R104_seed1.yaml", "scenarios/site_office/C100_seed1.yaml",
                                     "scenarios/site_office/S100_seed1.yaml"};
  std::vector<std::string> plans;  // more: a few start rooms of each plan's storey (--plan)
  std::string storey = "0";
  int rooms_per_plan = 3;
  std::string method = "sgraph";
  double duration_s = 0;  // 0: each scenario's own
  bool multi_storey = false;  // the --plan runs tour every storey the stairs reach (docs/multi_storey.md)
  bool altitude = false;      // ... with the barometer's altitude given to the localizer
  int rounds = 2;
  bool json = false;
};

// Start rooms spread over the plan's storey (every k-th room), as `bimloc run --all-rooms`.
std::vector<Scenario> planScenarios(const LoopBenchArgs& args) {
  std::vector<Scenario> out;
  for (const auto& plan : args.plans) {
    const World world = World::load(plan);
    RoomScenarioOptions o;
    o.plan = plan, o.storey = args.storey, o.method = args.method;
    const auto all = roomScenarios(world, o);
    const std::size_t step = std::max<std::size_t>(1, all.size() / static_cast<std::size_t>(std::max(1, args.rooms_per_plan)));
    for (std::size_t i = 0, taken = 0; i < all.size() && static_cast<int>(taken) < args.rooms_per_plan; i += step, ++taken) {
      out.push_back(args.multi_storey ? multiStoreyTour(all[i]) : all[i]);
      out.back().barometer.enabled = out.back().barometer.enabled || args.altitude;
      out.back().name = std::filesystem::path(plan).stem().string() + " " + out.back().name;
    }
  }
  return out;
}

// The localizer's time per simulated second in the first and the last full minute of the run:
// flat when its cost does not grow with the walk (the S-Graph's window, the filter's window).
std::string minutes(const ScenarioResult& r) {
  const auto full = static_cast<std::size_t>(r.sim_seconds / 60.0 + 1e-6);  // minutes not cut short
  const auto& m = r.localizer_seconds_by_minute;
  if (full < 2 || m.size() < full) return "-";
  return bimloc::cli::fixed(1000.0 * m.front() / 60.0, 1) + " / " + bimloc::cli::fixed(1000.0 * m[full - 1] / 60.0, 1);
}

double seconds(Clock::time_point t0) { return std::chrono::duration<double>(Clock::now() - t0).count(); }

constexpr const char* kLegend =
    "faces: the storey's wall faces. sim: seconds simulated. tour: the tour's planning (wall clock, in neither factor). "
    "x: times real time (simulated seconds per second): sim, the simulator alone; loop, the whole loop (wall clock); "
    "CPU, the whole loop in CPU time; search and track, its CPU while the localizer searches and while it tracks "
    "(on the line \"all\", min: the slowest run's). loc.: the localizer's share of the loop. ms/s: the localizer's "
    "milliseconds per simulated second in the first / the last full minute.";

void run(const LoopBenchArgs& args) {
  nlohmann::json rows = nlohmann::json::array();
  // Short headers, so that the table fits a terminal (the legend below names them in full).
  bimloc::cli::Table table({"scenario", "faces", "sim [s]", "tour [s]", "sim x", "loop x", "CPU x", "search x", "track x", "loc.",
                            "ms/s"});
  double total_sim = 0, total_loop = 0, total_alone = 0, total_loop_cpu = 0, total_setup = 0, total_localizer = 0;
  double worst_search = 1e300, worst_tracking = 1e300;  // the slowest run's factor in each phase
  std::vector<Scenario> scenarios;
  for (const auto& file : args.scenarios) scenarios.push_back(loadScenario(file));
  for (auto& s : planScenarios(args)) scenarios.push_back(std::move(s));
  for (auto& s : scenarios) {
    s.localizer["method"] = args.method;
    if (args.duration_s > 0) s.duration_s = args.duration_s, s.motion.explore_after_tour = true, s.expect.max_convergence_time_s = args.duration_s;
  }
  for (const auto& scenario : scenarios) {
    const std::string& file = scenario.name;
    const World world = World::load(scenario.world);
    const std::size_t storey = scenarioStorey(scenario, world);
    std::size_t faces = 0;
    for (const auto& w : world.building().storeys[storey].walls) faces += w.faces.size();
    // Best of the rounds, the two measurements interleaved: the machine's noise hits both alike.
    // The simulator's setup (the tour planned through the storey, the odometry drawn) happens
    // once before the first turn, as loading the world does: it is timed on its own and left
    // out of both real-time factors, which are those of the loop the robot runs in.
    double alone = 1e300, loop = 1e300, loop_cpu = 1e300, setup = 1e300;
    // Per phase, the loop's CPU seconds per turn (sim/runner: the setup is in neither phase):
    // the search (until convergence) and the tracking cost differently per update.
    double search_cpu = 1e300, tracking_cpu = 1e300;
    // The localizer's own wall seconds (its steps, less the turns cast and de-skewed in them:
    // the loop casts only the turns a localizer reads, so the loop less the simulator alone,
    // which casts every turn, is no longer the localizer's share).
    double localizer = 1e300;
    ScenarioResult result;
    for (int round = 0; round < std::max(1, args.rounds); ++round) {
      auto t0 = Clock::now();
      const Simulator sim(scenario, world);
      setup = std::min(setup, seconds(t0));
      t0 = Clock::now();
      std::size_t points = 0;
      sim.castTurns(1, [&](LidarScan&& scan) { points += scan.points.size(); });
      const auto odometry = sim.odometry();
      alone = std::min(alone, seconds(t0));
      t0 = Clock::now();
      result = bimloc::cli::runChecked(scenario, world, /*room_mode=*/true);  // as `run` does
      loop = std::min(loop, seconds(t0) - result.setup_seconds);
      localizer = std::min(localizer, std::accumulate(result.localizer_seconds_by_minute.begin(),
                                                      result.localizer_seconds_by_minute.end(), 0.0));
      // The turns' CPU seconds (sim/runner): the setup's, timed apart, is not in them (its wall
      // seconds, subtracted from the process's CPU time, over-subtract on a loaded machine).
      loop_cpu = std::min(loop_cpu, result.search_cpu_seconds + result.tracking_cpu_seconds);
      search_cpu = std::min(search_cpu, result.search_cpu_seconds), tracking_cpu = std::min(tracking_cpu, result.tracking_cpu_seconds);
    }
    const auto factor = [](double sim_s, double cpu_s) -> nlohmann::json {
      if (sim_s <= 0.0) return nullptr;
      return sim_s / std::max(cpu_s, 1e-9);
    };
    const nlohmann::json search_rt = factor(result.search_sim_seconds, search_cpu);
    const nlohmann::json tracking_rt = factor(result.tracking_sim_seconds, tracking_cpu);
    if (search_rt.is_number()) worst_search = std::min(worst_search, search_rt.get<double>());
    if (tracking_rt.is_number()) worst_tracking = std::min(worst_tracking, tracking_rt.get<double>());
    const double sim_s = result.sim_seconds;
    total_sim += sim_s, total_loop += loop, total_alone += alone, total_loop_cpu += loop_cpu, total_setup += setup;
    total_localizer += localizer;
    rows.push_back({{"scenario", file},
                    {"wall_faces", faces},
                    {"sim_seconds", sim_s},
                    {"setup_wall_seconds", setup},
                    {"simulator_wall_seconds", alone},
                    {"loop_wall_seconds", loop},
                    {"simulator_real_time_factor", sim_s / alone},
                    {"loop_real_time_factor", sim_s / loop},
                    {"loop_cpu_seconds", loop_cpu},
                    {"loop_cpu_real_time_factor", sim_s / loop_cpu},
                    {"localizer_share", localizer / loop},
                    {"search_sim_seconds", result.search_sim_seconds},
                    {"search_cpu_seconds", search_cpu},
                    {"search_cpu_real_time_factor", search_rt},
                    {"tracking_sim_seconds", result.tracking_sim_seconds},
                    {"tracking_cpu_seconds", tracking_cpu},
                    {"tracking_cpu_real_time_factor", tracking_rt},
                    {"converged", result.converged},
                    {"method", result.method},
                    {"localizer_seconds_by_minute", result.localizer_seconds_by_minute}});
    using bimloc::cli::fixed;
    table.add({scenario.name, std::to_string(faces), fixed(sim_s, 1), fixed(setup, 2), fixed(sim_s / alone, 1), fixed(sim_s / loop, 1),
               fixed(sim_s / loop_cpu, 1), search_rt.is_number() ? fixed(search_rt.get<double>(), 1) : "-",
               tracking_rt.is_number() ? fixed(tracking_rt.get<double>(), 1) : "-", fixed(100.0 * localizer / loop, 0) + " %",
               minutes(result)});
  }
  const nlohmann::json summary = {{"sim_seconds", total_sim},
                                  {"setup_wall_seconds", total_setup},
                                  {"loop_real_time_factor", total_sim / total_loop},
                                  {"loop_cpu_real_time_factor", total_sim / total_loop_cpu},
                                  {"simulator_real_time_factor", total_sim / total_alone},
                                  {"localizer_share", total_localizer / total_loop},
                                  {"slowest_search_cpu_real_time_factor", worst_search < 1e300 ? nlohmann::json(worst_search) : nlohmann::json()},
                                  {"slowest_tracking_cpu_real_time_factor",
                                   worst_tracking < 1e300 ? nlohmann::json(worst_tracking) : nlohmann::json()}};
  if (args.json) {
    std::cout << nlohmann::json{{"threads", 1}, {"rounds", args.rounds}, {"runs", rows}, {"summary", summary}}.dump() << "\n";
    return;
  }
  using bimloc::cli::fixed;
  table.add({"all", "", fixed(total_sim, 1), fixed(total_setup, 2), fixed(total_sim / total_alone, 1), fixed(total_sim / total_loop, 1),
             fixed(total_sim / total_loop_cpu, 1), worst_search < 1e300 ? "min " + fixed(worst_search, 1) : "-",
             worst_tracking < 1e300 ? "min " + fixed(worst_tracking, 1) : "-", fixed(100.0 * total_localizer / total_loop, 0) + " %", ""});
  std::cout << "one core, best of " << args.rounds << " rounds\n\n";
  table.print(std::cout);
  std::cout << "\n" << bimloc::cli::wrapText(kLegend, bimloc::cli::kTableColumns);
}

}  // namespace

void addBenchLoopCommand(CLI::App& bench) {
  auto args = std::make_shared<LoopBenchArgs>();
  CLI::App* cmd = bench.add_subcommand(
      "loop",
      "Real-time factor of the whole loop on one core (simulator, plane extraction, particle filter, path "
      "evidence: `bimloc run --jobs 1`), against the simulator alone on the same scenarios. The simulator's setup "
      "(the tour planned through the storey) is timed in its own column and left out of both factors.");
  cmd->add_option("scenarios", args->scenarios, "scenario files")->capture_default_str();
  cmd->add_option("--plan", args->plans, "also start rooms of this plan's storey (repeatable): cost against building size");
  cmd->add_option("--storey", args->storey, "storey of the --plan plans")->capture_default_str();
  cmd->add_option("--rooms-per-plan", args->rooms_per_plan, "start rooms per --plan, spread over the storey")
      ->check(CLI::Range(1, 1000))->capture_default_str();
  cmd->add_option("--method", args->method,
                  std::string("method of every run (over the scenario files' own): ") + bimloc::cli::kMethodHelp)
      ->check(bimloc::cli::methodCheck())->capture_default_str();
  cmd->add_option("--duration", args->duration_s, "seconds of every run (over the scenarios' own; longer tours explore on)")
      ->check(CLI::Range(1.0, 7200.0));
  cmd->add_flag("--multi-storey", args->multi_storey,
                "the --plan runs tour every storey the plan's stairs reach from their start, up and down the flights, as "
                "`bimloc run --multi-storey` (docs/multi_storey.md); the scenario files' runs are unchanged: the reference");
  cmd->add_flag("--altitude", args->altitude, "the --plan runs give the localizer the base's altitude as a barometer reads it");
  cmd->add_option("--rounds", args->rounds, "measurements of each, the best kept")->capture_default_str()->check(CLI::Range(1, 100));
  cmd->add_flag("--json", args->json, "print one JSON object");
  cmd->callback([args] { run(*args); });
}
