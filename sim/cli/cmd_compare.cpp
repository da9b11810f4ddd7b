// bimloc compare --plan P [--storey S] (--all-rooms | --rooms A,B,C) [--seeds K] [--methods M,...]
//                [--duration S] [--site PRESET] [--config FILE] [--jobs N] [--json] [--wide] [--out DIR]
// The paper's comparison (tables "Convergence time" and "ATE after convergence") on any plan:
// each (start room, seed) is simulated once and every method's localizer is stepped on the
// same turn before the next is made, so all get the same scans and the same odometry, bit for
// bit; each declares convergence by its own criterion and one scorer (RunScore) judges all.
#include "sim/cli/commands.hpp"
#include "sim/common/printable.hpp"
#include "sim/cli/compare_page.hpp"
#include "sim/cli/compare_report.hpp"
#include "sim/cli/run_pool.hpp"
#include "sim/cli/snapshots.hpp"
#include "sim/runner/room_scenarios.hpp"
#include "sim/common/atomic_file.hpp"

#include <algorithm>
#include <chrono>
#include <filesystem>
#include <iostream>

namespace {

using namespace bimloc::sim;

struct CompareArgs {
  std::string plan;
  std::string storey = "0";
  bool all_rooms = false;
  std::vector<std::string> rooms;
  int seeds = 1;
  std::vector<std::string> methods{"sgraph", "pf", "pf-no-rooms", "amcl", "ndt"};
  double duration_s = 120.0;
  std::string site;
  std::string config;
  int jobs = 1;
  bool json = false;
  bool wide = false;
  std::string out;
};

// A run's pictures of one method in DIR/snapshots/METHOD/RUN/ (N_PHASE.png by N, then
// errors.png), as paths relative to DIR.
std::vector<std::string> picturesOf(const std::string& dir, const std::string& method, const std::string& run) {
  namespace fs = std::filesystem;
  const std::string relative = "snapshots/" + bimloc::cli::fileSafe(method) + "/" + bimloc::cli::fileSafe(run);
  std::vector<std::pair<long, std::string>> files;
  if (fs::is_directory(dir + "/" + relative))
    for (const auto& e : fs::directory_iterator(dir + "/" + relative)) {
      const std::string name = e.path().filename().string();
      if (e.path().extension() != ".png") continue;
      // Snapshots in the order they were taken, the error plot last.
      const long order = name == "errors.png" ? 1L << 30 : std::strtol(name.c_str(), nullptr, 10);
      files.emplace_back(order, relative + "/" + name);
    }
  std::sort(files.begin(), files.end());
  std::vector<std::string> out;
  for (auto& f : files) out.push_back(std::move(f.second));
  return out;
}

void check(const CompareArgs& args) {
  if (args.all_rooms == !args.rooms.empty())
    throw std::invalid_argument(args.all_rooms ? "give --all-rooms or --rooms A,B,C, not both"
                                               : "which start rooms? give --all-rooms or --rooms A,B,C");
  if (args.storey == "auto")
    throw std::invalid_argument("--storey auto: compare needs the storey (the peers amcl and ndt localize on a known one)");
  for (std::size_t i = 0; i < args.methods.size(); ++i)
    if (std::find(args.methods.begin(), args.methods.begin() + static_cast<long>(i), args.methods[i]) !=
        args.methods.begin() + static_cast<long>(i))
      throw std::invalid_argument("--methods: '" + args.methods[i] + "' given twice");
}

void run(const CompareArgs& args) {
  check(args);
  bimloc::cli::WorldCache worlds;
  const World& world = worlds.get(args.plan);
  RoomScenarioOptions o;
  o.plan = args.plan, o.storey = args.storey, o.seeds = args.seeds, o.duration_s = args.duration_s;
  std::vector<Scenario> scenarios = roomScenarios(world, o);  // the same runs as `run --all-rooms`
  bimloc::cli::keepStartRooms(scenarios, args.rooms);
  if (scenarios.empty()) throw std::runtime_error(args.plan + ": storey '" + args.storey + "' has no room to start in");
  if (!args.config.empty()) bimloc::cli::applyConfig(scenarios, args.config);
  // AMCL's ROS defaults model poor wheel odometry (odom_alpha 0.2): on the bench's legged
  // odometry its particles never get tight enough to declare convergence. Say so up front.
  const bool amcl = std::find(args.methods.begin(), args.methods.end(), "amcl") != args.methods.end();
  if (amcl && !scenarios.front().localizer.contains("amcl"))
    std::cerr << "note: amcl runs with the ROS defaults (odom_alpha1..4 0.2, for poor wheel odometry); for the bench's "
                 "legged odometry, as the ROS amcl documentation advises, add --config scenarios/configs/amcl_legged.yaml\n";
  if (!args.site.empty())
    for (auto& s : scenarios) s.site = sitePreset(args.site);
  // The output folder is refused (or made) before the runs, not after minutes of them.
  std::optional<StagingDirectory> staging;
  if (!args.out.empty()) staging.emplace(args.out, OutputKind{"compare.json", "bimloc.compare"});

  const auto start = std::chrono::steady_clock::now();
  std::vector<bimloc::cli::CompareRun> runs(scenarios.size());
  const std::string label = "comparing " + std::to_string(scenarios.size()) + " runs x " + std::to_string(args.methods.size()) + " methods";
  bimloc::cli::forEachInParallel(scenarios.size(), args.jobs, label, [&](std::size_t i) {
    const Scenario& s = scenarios[i];
    runs[i].room = s.start.room, runs[i].seed = s.seed, runs[i].name = s.name;
    // With --out, each method's snapshots and error plot in DIR/snapshots/METHOD/RUN/.
    std::vector<SnapshotHook> hooks;
    const auto folderOf = [&](const std::string& method) { return staging->path() + "/snapshots/" + bimloc::cli::fileSafe(method); };
    if (staging)
      for (const auto& method : args.methods)
        hooks.push_back(bimloc::cli::snapshotWriter(world, s, folderOf(method), s.name + " - " + method));
    try {
      runs[i].results = bimloc::cli::runCheckedMethods(s, world, /*room_mode=*/true, args.methods, hooks);
      if (staging)
        for (std::size_t k = 0; k < args.methods.size(); ++k) {
          bimloc::cli::writeErrorPlot(folderOf(args.methods[k]), s.name, runs[i].results[k], s.name + " - " + args.methods[k]);
          runs[i].pictures.push_back(picturesOf(staging->path(), args.methods[k], s.name));
        }
    } catch (const std::exception& e) {
      runs[i].error = e.what();
    }
  });
  const double wall = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();

  bimloc::cli::CompareSetup setup;
  setup.plan = args.plan, setup.storey = world.building().storeyLabel(world.storeyIndex(args.storey));
  setup.site = args.site.empty() ? "exact" : args.site, setup.duration_s = args.duration_s, setup.seeds = args.seeds;
  setup.methods = args.methods;
  const nlohmann::json report = bimloc::cli::compareReport(setup, runs, wall);
  if (staging) {
    writeFileAtomically(staging->file("compare.json"), report.dump(1) + "\n");
    bimloc::cli::writeCompareFigures(setup, runs, staging->path());
    bimloc::cli::writeComparePage(report, staging->path());
    staging->commit();
  }
  if (args.json)
    std::cout << report.dump() << "\n";
  else
    bimloc::cli::printCompareTables(report, std::cout, args.wide);
  if (staging && !args.json) std::cout << "\nThe page: " << (std::filesystem::path(args.out) / "index.html").string() << "\n";
  for (const auto& r : runs)
    if (!r.error.empty()) std::cerr << "bimloc compare: error: " << r.name << ": " << printable(r.error) << "\n";
  if (report["errors"].get<int>() > 0) throw bimloc::cli::ExitCode{1};
}

}  // namespace

void addCompareCommand(CLI::App& app) {
  auto args = std::make_shared<CompareArgs>();
  CLI::App* cmd = app.add_subcommand(
      "compare",
      "Compare localization methods on the same simulated runs, as the paper's tables do: every start room of a\n"
      "storey (or the rooms given), --seeds runs each, each run simulated once and every method stepped on the same\n"
      "turns (the same scans and odometry, bit for bit). Each method declares convergence by its own criterion;\n"
      "one scorer judges all: N.L. when not converged by the end, a false convergence ('!') when declared while\n"
      "more than 0.5 m or 10 deg off. Prints the convergence-time table and the ATE table (with a summary per\n"
      "method); --out DIR also writes compare.json and two figures: convergence_times.png (a bar per run and\n"
      "method) and errors_over_time.png (each method's median position error over time). Exit status 1 when a\n"
      "run could not be made; a method that does not localize is a result, not an error.");
  cmd->add_option("--plan", args->plan, "IFC plan (or extract folder)")->required();
  cmd->add_option("--storey", args->storey, bimloc::cli::kStoreyHelp)->capture_default_str();
  cmd->add_flag("--all-rooms", args->all_rooms, "start in every room of the storey");
  cmd->add_option("--rooms", args->rooms, "start only in these rooms (comma-separated)")->delimiter(',');
  cmd->add_option("--seeds", args->seeds, "runs per start room (seeds 1..K: the same runs as `bimloc run --all-rooms`)")
      ->check(CLI::Range(1, 1000))
      ->capture_default_str();
  cmd->add_option("--methods", args->methods, std::string("comma-separated, each one of: ") + bimloc::cli::kMethodHelp)
      ->delimiter(',')
      ->check(bimloc::cli::methodCheck())
      ->capture_default_str();
  cmd->add_option("--duration", args->duration_s,
                  "seconds per run; the paper's AMCL took 168-233 s to converge, so short runs leave it N.L.")
      ->check(CLI::Range(1.0, 3600.0))
      ->capture_default_str();
  cmd->add_option("--site", args->site,
                  "simulate a site that is not its plan: exact, as_built, construction or heavy (every method still gets "
                  "only the plan)")
      ->check(bimloc::cli::siteCheck());
  cmd->add_option("--config", args->config,
                  "YAML file of localizer settings (a scenario's `localizer:` keys, e.g. `amcl: {...}`); each method "
                  "reads its own sections, `method` is the comparison's")
      ->check(CLI::ExistingFile);
  cmd->add_option("--jobs", args->jobs, "runs in parallel (the output is the same whatever the number)")
      ->check(CLI::Range(1, 256))
      ->capture_default_str();
  cmd->add_flag("--json", args->json, "print one JSON object (compare.json's) instead of the tables");
  cmd->add_flag("--wide", args->wide,
                "print each table whole, however wide (by default they are split to fit 100 columns), and the position "
                "error at the end of each run");
  cmd->add_option("--out", args->out,
                  "folder for compare.json, convergence_times.png, errors_over_time.png, snapshots/ and index.html (all "
                  "or nothing)");
  cmd->callback([args] { run(*args); });
}
