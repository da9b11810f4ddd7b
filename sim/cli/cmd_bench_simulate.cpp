// bimloc bench simulate [SCENARIO] [--json]
// Simulated seconds per wall second for a whole scenario (trajectory, odometry, lidar turns;
// no file output), at 1 and 2 threads: the simulator alone, against real time.
#include "sim/cli/commands.hpp"
#include "sim/cli/table.hpp"
#include "sim/simulation/simulator.hpp"

#include <chrono>
#include <iostream>

namespace {

using namespace bimloc::sim;
using Clock = std::chrono::steady_clock;

struct SimBenchArgs {
  std::string scenario = "scenarios/site_office_R101.yaml";
  std::vector<int> threads{1, 2};
  bool json = false;
};

void run(const SimBenchArgs& args) {
  const Scenario scenario = loadScenario(args.scenario);
  const World world = World::load(scenario.world);
  nlohmann::json rows = nlohmann::json::array();
  bimloc::cli::Table table({"threads", "simulated [s]", "wall [s]", "x real time"});
  for (const int threads : args.threads) {
    const auto t0 = Clock::now();
    const Simulator sim(scenario, world);
    std::size_t points = 0;
    sim.castTurns(threads, [&](LidarScan&& scan) { points += scan.points.size(); });
    const auto odometry = sim.odometry();
    const double wall = std::chrono::duration<double>(Clock::now() - t0).count();
    rows.push_back({{"threads", threads}, {"sim_seconds", scenario.duration_s}, {"wall_seconds", wall},
                    {"real_time_factor", scenario.duration_s / wall}, {"turns", sim.turnCount()}, {"points", points}});
    using bimloc::cli::fixed;
    table.add({std::to_string(threads), fixed(scenario.duration_s, 1), fixed(wall, 2), fixed(scenario.duration_s / wall, 1)});
  }
  if (args.json) {
    std::cout << nlohmann::json{{"scenario", args.scenario}, {"runs", rows}}.dump() << "\n";
  } else {
    std::cout << args.scenario << "\n\n";
    table.print(std::cout);
  }
}

}  // namespace

void addBenchSimulateCommand(CLI::App& bench) {
  auto args = std::make_shared<SimBenchArgs>();
  CLI::App* cmd = bench.add_subcommand(
      "simulate", "Real-time factor of the simulator alone (no output files) for a whole scenario, at 1 and 2 threads.");
  cmd->add_option("scenario", args->scenario, "scenario file")->capture_default_str();
  cmd->add_option("--threads", args->threads, "thread counts to measure")->capture_default_str();
  cmd->add_flag("--json", args->json, "print one JSON object");
  cmd->callback([args] { run(*args); });
}
