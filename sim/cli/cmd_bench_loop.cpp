// bimloc bench loop [SCENARIO...] [--rounds N] [--json]
// The whole loop on one core: simulator and localizer (plane extraction, particle filter, path
// evidence) as `bimloc run --jobs 1` runs them, against the simulator alone on the same
// scenario in the same run. Real-time factors, and the localizer's share of the loop.
#include "sim/cli/commands.hpp"
#include "sim/cli/table.hpp"
#include "sim/runner/run_scenario.hpp"
#include "sim/simulation/simulator.hpp"

#include <algorithm>
#include <chrono>
#include <iostream>

namespace {

using namespace bimloc::sim;
using Clock = std::chrono::steady_clock;

struct LoopBenchArgs {
  std::vector<std::string> scenarios{"scenarios/site_office/R104_seed1.yaml", "scenarios/site_office/C100_seed1.yaml",
                                     "scenarios/site_office/S100_seed1.yaml"};
  int rounds = 2;
  bool json = false;
};

double seconds(Clock::time_point t0) { return std::chrono::duration<double>(Clock::now() - t0).count(); }

void run(const LoopBenchArgs& args) {
  nlohmann::json rows = nlohmann::json::array();
  bimloc::cli::Table table({"scenario", "simulated [s]", "simulator alone [x RT]", "whole loop [x RT]", "localizer share"});
  double total_sim = 0, total_loop = 0, total_alone = 0;
  for (const auto& file : args.scenarios) {
    const Scenario scenario = loadScenario(file);
    const World world = World::load(scenario.world);
    // Best of the rounds, the two measurements interleaved: the machine's noise hits both alike.
    double alone = 1e300, loop = 1e300;
    ScenarioResult result;
    for (int round = 0; round < std::max(1, args.rounds); ++round) {
      auto t0 = Clock::now();
      const Simulator sim(scenario, world);
      std::size_t points = 0;
      sim.castTurns(1, [&](LidarScan&& scan) { points += scan.points.size(); });
      const auto odometry = sim.odometry();
      alone = std::min(alone, seconds(t0));
      t0 = Clock::now();
      result = runScenario(scenario, world);
      loop = std::min(loop, seconds(t0));
    }
    const double sim_s = result.sim_seconds;
    total_sim += sim_s, total_loop += loop, total_alone += alone;
    rows.push_back({{"scenario", file},
                    {"sim_seconds", sim_s},
                    {"simulator_wall_seconds", alone},
                    {"loop_wall_seconds", loop},
                    {"simulator_real_time_factor", sim_s / alone},
                    {"loop_real_time_factor", sim_s / loop},
                    {"localizer_share", 1.0 - alone / loop},
                    {"converged", result.converged}});
    using bimloc::cli::fixed;
    table.add({scenario.name, fixed(sim_s, 1), fixed(sim_s / alone, 1), fixed(sim_s / loop, 1),
               fixed(100.0 * (1.0 - alone / loop), 0) + " %"});
  }
  const nlohmann::json summary = {{"sim_seconds", total_sim},
                                  {"loop_real_time_factor", total_sim / total_loop},
                                  {"simulator_real_time_factor", total_sim / total_alone},
                                  {"localizer_share", 1.0 - total_alone / total_loop}};
  if (args.json) {
    std::cout << nlohmann::json{{"threads", 1}, {"rounds", args.rounds}, {"runs", rows}, {"summary", summary}}.dump() << "\n";
    return;
  }
  using bimloc::cli::fixed;
  table.add({"all", fixed(total_sim, 1), fixed(total_sim / total_alone, 1), fixed(total_sim / total_loop, 1),
             fixed(100.0 * (1.0 - total_alone / total_loop), 0) + " %"});
  std::cout << "one core, best of " << args.rounds << " rounds\n\n";
  table.print(std::cout);
}

}  // namespace

void addBenchLoopCommand(CLI::App& bench) {
  auto args = std::make_shared<LoopBenchArgs>();
  CLI::App* cmd = bench.add_subcommand(
      "loop",
      "Real-time factor of the whole loop on one core (simulator, plane extraction, particle filter, path "
      "evidence: `bimloc run --jobs 1`), against the simulator alone on the same scenarios.");
  cmd->add_option("scenarios", args->scenarios, "scenario files")->capture_default_str();
  cmd->add_option("--rounds", args->rounds, "measurements of each, the best kept")->capture_default_str()->check(CLI::Range(1, 100));
  cmd->add_flag("--json", args->json, "print one JSON object");
  cmd->callback([args] { run(*args); });
}
