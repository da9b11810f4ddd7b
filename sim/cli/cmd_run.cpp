// bimloc run SCENARIO... | --plan PLAN --all-rooms [--storey S|auto] [--method M] [--config FILE.yaml] [--starts rooms|outside] [--json] [--out DIR] [--jobs N] [--shard K/N] [--oracle] [--multi-storey] [--altitude]
#include "sim/cli/commands.hpp"
#include "sim/common/printable.hpp"
#include "sim/cli/run_pool.hpp"
#include "sim/cli/run_report.hpp"
#include "sim/cli/shards.hpp"
#include "sim/runner/room_scenarios.hpp"
#include "sim/scenario/yaml_mapping.hpp"

#include <algorithm>
#include <chrono>
#include <iostream>

namespace {

using namespace bimloc::sim;

struct RunArgs {
  std::vector<std::string> scenarios;
  std::string plan;
  std::string storey = "0";
  bool all_rooms = false;
  std::string starts = "rooms";
  int seeds = 1;
  std::string method = "sgraph";
  bool method_given = false;  // --method on the command line: over the scenario files' own too
  std::string config;
  double duration_s = 40.0;
  bool duration_given = false;
  bool json = false;
  std::string out;
  std::string trace;
  int jobs = 1;
  std::vector<std::string> rooms, prior_rooms;
  std::string prior_pose;
  std::string site;  // --site PRESET: every scenario's site (sim/world/site_config.hpp)
  std::string shard;  // K/N: only the K-th of N slices of the scenario list (sim/cli/shards.hpp)
  std::string tum;    // folder for each scenario's truth.tum and estimate.tum
  bool oracle = false;  // --oracle: each run's information limit (docs/oracle.md)
  bool multi_storey = false;  // --multi-storey: every storey the stairs reach (docs/multi_storey.md)
  bool altitude = false;      // --altitude: the localizer is given a barometer's altitude
  std::string motion = "tour";  // --motion tour|disambiguate (docs/disambiguate.md)
  bool no_deskew = false;        // --no-deskew: the turns as cast (sensor.deskew false)
};

void run(const RunArgs& args) {
  const std::optional<bimloc::cli::ShardSpec> shard =
      args.shard.empty() ? std::nullopt : std::optional(bimloc::cli::parseShard(args.shard));
  std::vector<Scenario> scenarios;
  bimloc::cli::WorldCache worlds;
  for (const auto& path : args.scenarios) scenarios.push_back(loadScenario(path));
  const bool generate = args.all_rooms || args.starts != "rooms";
  if (generate) {
    if (args.plan.empty()) throw std::runtime_error("--all-rooms and --starts need --plan PLAN");
    RoomScenarioOptions o;
    o.plan = args.plan, o.storey = args.storey, o.seeds = args.seeds, o.method = args.method, o.duration_s = args.duration_s;
    o.starts = args.starts;
    const World& world = worlds.get(args.plan);
    auto generated = roomScenarios(world, o);
    if (generated.empty()) {
      // A storey without rooms (or, with --storey auto, a plan without a storey of rooms and
      // walls): say which, not that no plan was given.
      if (args.storey == "auto") throw std::runtime_error(args.plan + ": no storey has both rooms and walls (`bimloc extract` lists them)");
      const std::size_t s = world.storeyIndex(args.storey);
      throw std::runtime_error(args.plan + ": storey " + std::to_string(s) + " '" + world.building().storeys[s].name +
                               "' has no rooms (no IfcSpace, and its walls close none to infer): nothing to start in "
                               "(`bimloc extract` lists each storey's rooms; --storey chooses another)");
    }
    bimloc::cli::keepStartRooms(generated, args.rooms);
    scenarios.insert(scenarios.end(), generated.begin(), generated.end());
  }
  if (scenarios.empty()) throw std::runtime_error("nothing to run: give scenario files, or --plan PLAN --all-rooms");
  bimloc::cli::applyPrior(scenarios, args.prior_rooms, args.prior_pose);
  if (!args.config.empty()) bimloc::cli::applyConfig(scenarios, args.config);
  for (std::size_t i = 0; i < args.scenarios.size(); ++i) {  // the files' own, unless the command line says
    if (args.method_given) scenarios[i].localizer["method"] = args.method;
    if (args.duration_given) scenarios[i].duration_s = args.duration_s;
  }
  if (!args.site.empty())
    for (auto& s : scenarios) s.site = sitePreset(args.site);
  for (auto& s : scenarios) {
    if (args.multi_storey) s = multiStoreyTour(std::move(s));
    s.barometer.enabled = s.barometer.enabled || args.altitude;
  }
  bimloc::cli::applyMotion(scenarios, args.motion);
  if (args.no_deskew)
    for (auto& s : scenarios) s.sensor.deskew = false;

  std::vector<bool> generated(scenarios.size());
  for (std::size_t i = args.scenarios.size(); i < scenarios.size(); ++i) generated[i] = generate;
  // With --shard, the slice of the whole list (every expansion done): what merge needs to put
  // it back in place, and to tell one sweep's shards from another's.
  std::vector<std::size_t> positions;
  std::string fingerprint;
  const std::size_t total = scenarios.size();
  if (shard) {
    fingerprint = bimloc::cli::sweepFingerprint(scenarios);
    std::vector<Scenario> kept;
    std::vector<bool> kept_generated;
    for (std::size_t i = 0; i < scenarios.size(); ++i)
      if (shard->contains(i)) positions.push_back(i), kept.push_back(scenarios[i]), kept_generated.push_back(generated[i]);
    scenarios = std::move(kept), generated = std::move(kept_generated);
  }

  // Scenarios in parallel, results in input order: the same output whatever --jobs.
  const auto start = std::chrono::steady_clock::now();
  bimloc::cli::RunPoolOptions pool;
  pool.jobs = args.jobs, pool.snapshots = args.out, pool.trace = args.trace, pool.tum = args.tum;
  pool.oracle = args.oracle;
  const auto runs = bimloc::cli::runPool(scenarios, generated, worlds, pool);
  std::vector<ScenarioResult> results;
  std::vector<std::string> errors;
  for (const auto& run : runs) results.push_back(run.result), errors.push_back(run.error);
  const double wall = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();

  auto report = bimloc::cli::runReport(results, wall);
  if (shard) report["shard"] = bimloc::cli::shardJson(*shard, total, fingerprint, positions);
  if (args.json)
    std::cout << report.dump() << "\n";
  else
    bimloc::cli::printRunTable(results, report, std::cout);
  for (std::size_t i = 0; i < errors.size(); ++i)
    if (!errors[i].empty()) std::cerr << "bimloc run: error: " << printable(errors[i]) << "\n";
  bool all_passed = true;
  for (const auto& r : results) all_passed = all_passed && r.passed;
  // A scenario that could not run (named above) did not localize either: its JSON entry says why.
  if (!all_passed) throw bimloc::cli::ExitCode{bimloc::cli::kExitNotLocalized};
}

}  // namespace

CLI::Validator bimloc::cli::siteCheck() {
  return CLI::Validator(
      [](const std::string& v) {  // a typo gets the nearest preset, as in scenario files
        const auto& names = sitePresetNames();
        if (std::find(names.begin(), names.end(), v) != names.end()) return std::string();
        const std::string guess = bimloc::sim::detail::nearestWord(v, names);
        return "no site preset '" + v + "' (exact, as_built, construction, heavy)" +
               (guess.empty() ? std::string() : "; did you mean '" + guess + "'?");
      },
      "");
}

void addRunCommand(CLI::App& app) {
  auto args = std::make_shared<RunArgs>();
  CLI::App* cmd = app.add_subcommand(
      "run",
      "Run scenarios in the loop: the simulator feeds scans and odometry at the sensor's rate into the localizer\n"
      "(the room-aware particle filter, then the S-Graph tracker), and each run is scored against the ground truth and the scenario's\n"
      "expectations: converged, convergence time, room found, errors, ATE, false convergence. Exit status\n"
      "(docs/exit_codes.md): 0 every scenario passed; 1 a scenario did not localize, localized falsely, missed an\n"
      "expectation or could not run (the others' results are printed); 2 nothing ran: bad options, a scenario file\n"
      "or plan that cannot be used. With --plan PLAN --all-rooms: one scenario per room of the storey; --starts outside:\n"
      "starts in no room (halls without a space, doorways, just outside); --storey auto: the localizer is not told\n"
      "the storey (every storey with walls and rooms is a candidate, the scans decide).");
  cmd->add_option("scenarios", args->scenarios, "scenario files (YAML)");
  cmd->add_option("--plan", args->plan, "IFC plan (or extract folder) for --all-rooms");
  cmd->add_option("--storey", args->storey,
                  std::string(bimloc::cli::kStoreyHelp) + " for --all-rooms / --starts; auto: every storey with walls and rooms, each run on "
                  "its true storey, the localizer not told which")
      ->capture_default_str();
  cmd->add_flag("--all-rooms", args->all_rooms, "one scenario per room of the storey: random start in it, walk out");
  cmd->add_option("--starts", args->starts,
                  "with --plan: rooms (a random start in each room, as --all-rooms) or outside (--seeds random starts in "
                  "no room per storey: halls without a space, doorways, up to 3 m outside the walls)")
      ->check(CLI::IsMember({"rooms", "outside"}))
      ->capture_default_str();
  cmd->add_option("--seeds", args->seeds, "seeds per room with --all-rooms; starts per storey with --starts outside")
      ->check(CLI::Range(1, 1000))
      ->capture_default_str();
  auto* method = cmd->add_option("--method", args->method, std::string(bimloc::cli::kMethodHelp) + "; over the scenario files' own when given")
                     ->check(bimloc::cli::methodCheck())
                     ->capture_default_str();
  auto* duration = cmd->add_option("--duration", args->duration_s, "seconds per --all-rooms scenario; over the scenario files' own when given")
                       ->check(CLI::Range(1.0, 3600.0))
                       ->capture_default_str();
  cmd->add_flag("--json", args->json, "print one JSON object instead of the table");
  cmd->add_option("--out", args->out, "folder for top-view PNG snapshots (initialization, clustering, convergence)");
  cmd->add_option("--trace", args->trace,
                  "folder for one CSV per scenario: a row per weighing (truth, estimate, the path evidence's best "
                  "place and margin)");
  cmd->add_option("--rooms", args->rooms, "with --all-rooms: only these start rooms (comma-separated)")->delimiter(',');
  cmd->add_option("--prior-room", args->prior_rooms,
                  "what you know of the start: it was in one of these rooms (comma-separated); places elsewhere are not "
                  "considered")
      ->delimiter(',');
  cmd->add_option("--prior-pose", args->prior_pose, "what you know of the start: x,y,yaw_deg,sigma_m (map frame)");
  cmd->add_option("--config", args->config,
                  "YAML file of localizer settings (the keys of a scenario's `localizer:`, e.g. `pf: {particles: 8000}`), "
                  "over every scenario's own")
      ->check(CLI::ExistingFile);
  cmd->add_option("--site", args->site,
                  "simulate every scenario on a site that is not its plan: exact, as_built, construction or heavy "
                  "(replaces the scenarios' site: sections; the localizer still gets only the plan)")
      ->check(bimloc::cli::siteCheck());
  cmd->add_option("--shard", args->shard,
                  "K/N: run only the K-th of N deterministic slices of the scenario list (every N-th from the K-th, after "
                  "--all-rooms x --seeds); with --json the output carries what `bimloc report merge` needs");
  cmd->add_option("--tum", args->tum,
                  "folder for each scenario's trajectories in the TUM format, for `bimloc eval` or evo: truth.tum (every "
                  "step) and estimate.tum (the steps the ATE scores: converged, not lost) in DIR/<scenario>/");
  cmd->add_option("--jobs", args->jobs, "scenarios run in parallel")->check(CLI::Range(1, 256))->capture_default_str();
  cmd->add_flag("--multi-storey", args->multi_storey,
                "the base tours every storey the plan's stairs reach from its start, an equal share of the duration on "
                "each, up and down the flights (docs/multi_storey.md)");
  cmd->add_flag("--altitude", args->altitude,
                "the localizer is given the base's altitude as a barometer reads it (noise, offset, drift: "
                "docs/multi_storey.md)");
  cmd->add_option("--motion", args->motion, bimloc::cli::kMotionHelp)->check(bimloc::cli::motionCheck())->capture_default_str();
  cmd->add_flag("--no-deskew", args->no_deskew, bimloc::cli::kNoDeskewHelp);
  cmd->add_flag("--oracle", args->oracle,
                "also each run's information limit (docs/oracle.md): decidable_at_s (from when the scans ruled out every "
                "place but the true one), decision_lag_s and decision_ratio; slow (its cost is in the JSON)");
  cmd->callback([args, method, duration] {
    args->method_given = method->count() > 0;
    args->duration_given = duration->count() > 0;
    run(*args);
  });
}
