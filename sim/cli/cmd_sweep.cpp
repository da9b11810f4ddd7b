// bimloc sweep PLAN... [--sites P,Q --methods M,N --plot F.png] [--seeds K] [--method M] [--duration S] [--storey auto] [--starts rooms|outside] [--jobs N] [--json] [--oracle] [--multi-storey] [--altitude]
// The paper's experiment over many plans at once: every room of every storey with rooms, K
// seeds each, and a row per plan and storey: how often it localized, how often falsely, how
// fast, how accurately, and the smallest path-evidence margin a convergence was accepted at.
// Generated worlds come from `bimloc worldgen --random`: this command only runs plans.
#include "sim/cli/commands.hpp"
#include "sim/cli/oracle_report.hpp"
#include "sim/cli/run_pool.hpp"
#include "sim/cli/run_report.hpp"
#include "sim/cli/sweep_sites.hpp"
#include "sim/cli/sweep_summary.hpp"
#include "sim/cli/table.hpp"
#include "sim/runner/room_scenarios.hpp"

#include <algorithm>
#include <chrono>
#include <filesystem>
#include <iostream>
#include <limits>
#include <tuple>
#include <vector>

namespace {

using namespace bimloc::sim;
using bimloc::cli::cell;
using bimloc::cli::fixed;
using bimloc::cli::runsThatRan;

struct SweepArgs {
  std::vector<std::string> plans;
  int seeds = 2;
  std::string method = "sgraph";
  double duration_s = 40.0;
  int jobs = 1;
  bool json = false;
  std::string storey;            // "auto": the localizer is not told the storey
  std::string starts = "rooms";  // or "outside"
  int rooms_per_storey = 0;      // 0: every room
  std::string site;              // --site PRESET: the simulated site of every run
  std::vector<std::string> sites, methods;  // --sites, --methods: the robustness sweep
  std::string plot;                         // --plot FILE.png (robustness sweep)
  std::vector<std::string> prior_rooms;
  std::string prior_pose;
  std::string config;  // --config FILE.yaml: localizer settings (each method reads its own sections)
  bool oracle = false;  // --oracle: each run's information limit (docs/oracle.md)
  bool multi_storey = false;  // --multi-storey: every storey the stairs reach (docs/multi_storey.md)
  bool altitude = false;      // --altitude: the localizer is given a barometer's altitude
  std::string motion = "tour";  // --motion tour|disambiguate (docs/disambiguate.md)
  bool no_deskew = false;        // --no-deskew: the turns as cast (sensor.deskew false)
};

// One row: a group of runs (a plan's storey, or all of them).
nlohmann::json summarise(const std::string& plan, const std::string& storey, const std::vector<const ScenarioResult*>& runs) {
  nlohmann::json row{{"plan", plan}, {"storey", storey}};
  row.update(bimloc::cli::summariseRuns(runs));
  return row;
}

// Start rooms spread over the storey (every k-th room, with all its seeds): long walks explore
// the whole storey from any start, so a few starts measure it.
std::vector<Scenario> spread(const std::vector<Scenario>& all, int rooms, int seeds) {
  const std::size_t per_room = static_cast<std::size_t>(std::max(1, seeds));
  const std::size_t room_count = all.size() / per_room;
  const std::size_t step = std::max<std::size_t>(1, room_count / static_cast<std::size_t>(rooms));
  std::vector<Scenario> out;
  for (std::size_t r = 0, taken = 0; r < room_count && static_cast<int>(taken) < rooms; r += step, ++taken)
    for (std::size_t k = 0; k < per_room; ++k) out.push_back(all[r * per_room + k]);
  return out;
}

void run(const SweepArgs& args) {
  bimloc::cli::WorldCache worlds;
  std::vector<Scenario> scenarios;
  // Plan, storey of each scenario: a row per storey, by its index (two buildings of one site
  // may each have a "Ground floor": their label says which).
  std::vector<std::tuple<std::string, std::size_t, std::string>> groups;
  for (const auto& plan : args.plans) {
    const World& world = worlds.get(plan);
    const auto& storeys = world.building().storeys;
    for (std::size_t s = 0; s < storeys.size(); ++s) {
      if (storeys[s].rooms.empty() || storeys[s].walls.empty()) continue;
      RoomScenarioOptions o;
      o.plan = plan, o.storey = std::to_string(s), o.seeds = args.seeds, o.method = args.method, o.duration_s = args.duration_s;
      o.starts = args.starts;
      auto generated = roomScenarios(world, o);
      if (args.rooms_per_storey > 0) generated = spread(generated, args.rooms_per_storey, args.seeds);
      for (auto& sc : generated) {
        // Each run on its true storey; with --storey auto the localizer is not told which.
        if (args.storey == "auto") sc.localizer["storey"] = "auto", sc.name = world.building().storeyLabel(s) + "/" + sc.name;
        scenarios.push_back(std::move(sc));
        groups.emplace_back(plan, s, world.building().storeyLabel(s));
      }
    }
  }
  if (scenarios.empty()) {
    // Name what was read and why nothing of it can be run (a bridge, a library of types, a plan
    // of walls with no room and none closed enough to infer one).
    std::string plans;
    for (const auto& plan : args.plans) plans += (plans.empty() ? "" : ", ") + plan;
    throw std::runtime_error(plans + ": no storey has both rooms and walls (`bimloc extract PLAN` lists each storey's rooms and walls; "
                                     "rooms are inferred only where walls close them)");
  }
  bimloc::cli::applyPrior(scenarios, args.prior_rooms, args.prior_pose);
  if (!args.config.empty()) bimloc::cli::applyConfig(scenarios, args.config);
  for (auto& s : scenarios) {
    s.localizer["method"] = args.method;  // the sweep's, over a config file's
    if (args.multi_storey) s = multiStoreyTour(std::move(s));
    s.barometer.enabled = s.barometer.enabled || args.altitude;
  }
  bimloc::cli::applyMotion(scenarios, args.motion);
  if (args.no_deskew)
    for (auto& s : scenarios) s.sensor.deskew = false;
  if (!args.sites.empty() || !args.methods.empty() || !args.plot.empty()) {
    bimloc::cli::RobustnessOptions o;
    o.sites = args.sites.empty() ? std::vector<std::string>{args.site.empty() ? "exact" : args.site} : args.sites;
    o.methods = args.methods.empty() ? std::vector<std::string>{args.method} : args.methods;
    o.plot = args.plot, o.json = args.json, o.jobs = args.jobs, o.oracle = args.oracle;
    std::string plans;
    for (const auto& p : args.plans) plans += (plans.empty() ? "" : ", ") + std::filesystem::path(p).filename().string();
    o.title = "robustness: " + plans + ", " + std::to_string(scenarios.size()) + (scenarios.size() == 1 ? " start, " : " starts, ") +
              fixed(args.duration_s, 0) + " s each";
    bimloc::cli::runRobustness(scenarios, worlds, o);  // degrading is what it measures: exit 0
    return;
  }
  if (!args.site.empty())
    for (auto& s : scenarios) s.site = sitePreset(args.site);
  const auto start = std::chrono::steady_clock::now();
  bimloc::cli::RunPoolOptions pool;
  pool.jobs = args.jobs, pool.progress_label = "sweeping " + std::to_string(scenarios.size()) + " runs";
  pool.oracle = args.oracle;
  const auto runs = bimloc::cli::runPool(scenarios, std::vector<bool>(scenarios.size(), true), worlds, pool);
  const double wall = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();

  nlohmann::json rows = nlohmann::json::array();
  std::vector<const ScenarioResult*> all;
  for (std::size_t i = 0; i < runs.size();) {
    std::vector<const ScenarioResult*> group;
    std::size_t j = i;
    for (; j < runs.size() && groups[j] == groups[i]; ++j) group.push_back(&runs[j].result), all.push_back(&runs[j].result);
    rows.push_back(summarise(std::filesystem::path(std::get<0>(groups[i])).filename().string(), std::get<2>(groups[i]), group));
    i = j;
  }
  nlohmann::json total = summarise("all", "", all);
  total["wall_seconds"] = wall;
  std::vector<ScenarioResult> results;
  for (const auto& r : runs) results.push_back(r.result);
  if (args.json) {
    std::cout << nlohmann::json{{"method", args.method}, {"seeds", args.seeds}, {"duration_s", args.duration_s},
                                {"site", args.site.empty() ? std::string("exact") : args.site},
                                {"groups", rows}, {"summary", total},
                                {"scenarios", bimloc::cli::runReport(results, wall)["scenarios"]}}
                     .dump()
              << "\n";
  } else {
    std::vector<std::string> header{"plan", "storey", "runs", "localized", "false", "median [s]", "p90 [s]", "max [s]",
                                    "median ATE [m]", "max ATE [m]", "RPE [m/m]", "map RMSE [m]", "lost", "path [m]", "min margin"};
    // With --oracle: decidable starts, those localized, the lag and the ratio (median / p90).
    if (args.oracle) header.insert(header.end(), {"decidable", "dec. localized", "lag [s]", "ratio", "oracle [s/run]"});
    bimloc::cli::Table table(header);
    rows.push_back(total);
    // A start that could not be run is listed below the table, not counted as not localized.
    for (const auto& g : rows) {
      std::vector<std::string> row{g["plan"], g["storey"], std::to_string(runsThatRan(g)),
                                   std::to_string(g["localized"].get<int>()),
                                   g["false_convergences"].get<int>() ? "FALSE " + std::to_string(g["false_convergences"].get<int>()) : "0",
                                   cell(g["median_convergence_s"], 1), cell(g["p90_convergence_s"], 1), cell(g["max_convergence_s"], 1),
                                   cell(g["median_ate_m"], 3), cell(g["max_ate_m"], 3), cell(g["median_rpe_m_per_m"], 3),
                                   cell(g["median_map_rmse_m"], 3), std::to_string(g["losses"].get<int>()), cell(g["median_path_length_m"], 0),
                                   cell(g["min_accepted_margin"], 1)};
      if (args.oracle && g.contains("decidable"))
        row.insert(row.end(), {std::to_string(g["decidable"].get<int>()), std::to_string(g["decidable_localized"].get<int>()),
                               cell(g["median_decision_lag_s"], 1) + " / " + cell(g["p90_decision_lag_s"], 1),
                               cell(g["median_decision_ratio"], 2) + " / " + cell(g["p90_decision_ratio"], 2),
                               cell(g["median_oracle_seconds"], 1)});
      table.add(row);
    }
    table.print(std::cout);
    const int not_run = total["errors"].get<int>();
    std::cout << "\n" << total["localized"].get<int>() << " of " << runsThatRan(total) << " localized, "
              << total["false_convergences"].get<int>() << " false convergences; " << fixed(wall, 0) << " s";
    if (not_run > 0) std::cout << "; " << not_run << (not_run == 1 ? " start" : " starts") << " could not be run (below)";
    std::cout << "\n";
  }
  for (const auto& r : runs)
    if (!r.error.empty()) std::cerr << "bimloc sweep: not run: " << r.result.name << ": " << r.error << "\n";
  // As `run`: every run localized, or not (a false convergence, none, or a start that could not run).
  if (total["localized"].get<int>() < static_cast<int>(runs.size())) throw bimloc::cli::ExitCode{bimloc::cli::kExitNotLocalized};
}

}  // namespace

void addSweepCommand(CLI::App& app) {
  auto args = std::make_shared<SweepArgs>();
  CLI::App* cmd = app.add_subcommand(
      "sweep",
      "Global localization from every room of every storey (with rooms) of each plan, several seeds each: a row per\n"
      "plan and storey with the localization rate, false convergences, convergence-time distribution, ATE and the\n"
      "smallest path-evidence margin a convergence was accepted at. Exit status (docs/exit_codes.md): 0 every run\n"
      "localized; 1 a run did not localize, localized falsely or could not run; 2 nothing ran (bad options, a plan\n"
      "that cannot be used). The robustness sweep (--sites, --methods, --plot) measures how the rate degrades: 0\n"
      "once it ran, 2 when it could not.\n"
      "Make hard plans with `bimloc worldgen --random SEED --random-count K --out DIR`, then sweep DIR/*.ifc.");
  cmd->add_option("plans", args->plans, "IFC plans (or extract folders)")->required();
  cmd->add_option("--seeds", args->seeds, "seeds per room")->check(CLI::Range(1, 1000))->capture_default_str();
  cmd->add_option("--method", args->method, bimloc::cli::kMethodHelp)
      ->check(bimloc::cli::methodCheck())
      ->capture_default_str();
  cmd->add_option("--rooms-per-storey", args->rooms_per_storey,
                  "start rooms per storey, spread over it (0: every room); long walks (--duration 300) explore the "
                  "whole storey from any start")
      ->check(CLI::Range(0, 100000))
      ->capture_default_str();
  cmd->add_option("--site", args->site,
                  "every run on a site that is not its plan: exact, as_built, construction or heavy (the localizer "
                  "still gets only the plan); one sweep per preset gives the robustness table")
      ->check(bimloc::cli::siteCheck());
  cmd->add_option("--sites", args->sites,
                  "robustness sweep: the same starts on each of these site presets (comma-separated, in order of "
                  "deviation: exact,as_built,construction,heavy); a row per preset and method")
      ->delimiter(',')
      ->check(bimloc::cli::siteCheck())
      ->excludes("--site");
  cmd->add_option("--methods", args->methods,
                  "robustness sweep: each of these methods (comma-separated, any --method value) on every preset")
      ->delimiter(',')
      ->check(bimloc::cli::methodCheck())
      ->excludes("--method");
  cmd->add_option("--plot", args->plot,
                  "robustness sweep: a PNG of the localization rate and the median ATE against the deviation level");
  cmd->add_option("--duration", args->duration_s, "seconds per run")->check(CLI::Range(1.0, 3600.0))->capture_default_str();
  cmd->add_option("--storey", args->storey,
                  "auto: the localizer is not told the storey (every storey with walls and rooms is a candidate); rows "
                  "stay per true storey, and a run converged on another storey counts as false")
      ->check(CLI::IsMember({"auto"}));
  cmd->add_option("--starts", args->starts,
                  "rooms (a random start in each room) or outside (--seeds random starts in no room per storey)")
      ->check(CLI::IsMember({"rooms", "outside"}))
      ->capture_default_str();
  cmd->add_option("--jobs", args->jobs, "runs in parallel")->check(CLI::Range(1, 256))->capture_default_str();
  cmd->add_flag("--json", args->json, "one JSON object: groups, summary, every run");
  cmd->add_option("--prior-room", args->prior_rooms, "the start was in one of these rooms (comma-separated)")->delimiter(',');
  cmd->add_option("--prior-pose", args->prior_pose, "the start was near x,y,yaw_deg,sigma_m (map frame)");
  cmd->add_option("--config", args->config,
                  "YAML file of localizer settings (a scenario's `localizer:` keys, e.g. `amcl: {...}`); each method reads "
                  "its own sections, the method is the sweep's")
      ->check(CLI::ExistingFile);
  cmd->add_flag("--multi-storey", args->multi_storey,
                "every run tours every storey the plan's stairs reach from its start, an equal share of the duration "
                "on each (docs/multi_storey.md)");
  cmd->add_flag("--altitude", args->altitude,
                "the localizer is given the base's altitude as a barometer reads it (docs/multi_storey.md)");
  cmd->add_option("--motion", args->motion, bimloc::cli::kMotionHelp)->check(bimloc::cli::motionCheck())->capture_default_str();
  cmd->add_flag("--no-deskew", args->no_deskew, bimloc::cli::kNoDeskewHelp);
  cmd->add_flag("--oracle", args->oracle,
                "also each run's information limit (docs/oracle.md): from when the scans ruled out every place but the "
                "true one (decidable_at_s), the localizer's lag and ratio beyond it, and the summary's quantiles; slow");
  cmd->callback([args] { run(*args); });
}
