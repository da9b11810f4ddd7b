// bimloc localize DATASET --plan PLAN [--storey S|auto] [--method sgraph|pf|pf-no-rooms|amcl|ndt] [--config FILE.yaml] [--json]
// The same localizer as `bimloc run`, offline, on a recorded dataset.
#include "sim/cli/commands.hpp"
#include "sim/cli/run_report.hpp"
#include "sim/dataset/dataset_reader.hpp"
#include "sim/metrics/map_error.hpp"
#include "sim/runner/evaluation.hpp"
#include "sim/world/world.hpp"

#include <bimloc/bim/ifc_reader.hpp>

#include <chrono>
#include <iostream>

namespace {

using namespace bimloc::sim;

struct LocalizeArgs {
  std::string dataset;
  std::string plan;
  std::string storey;
  std::string method = "sgraph";
  std::string config;
  std::uint64_t seed = 0;
  bool json = false;
};

void run(const LocalizeArgs& args) {
  const auto start = std::chrono::steady_clock::now();
  const RecordedDataset data = readDataset(args.dataset);
  const bimloc::bim::Building building = bimloc::bim::readIfc(args.plan, {});
  const bool storey_auto = args.storey == "auto";
  // The true storey, for scoring: as recorded (with auto, the localizer is not told it).
  const std::string storey_name =
      !args.storey.empty() && !storey_auto ? args.storey : (data.storey.empty() ? "0" : data.storey);
  const bimloc::bim::Storey* storey = building.findStorey(storey_name);
  if (!storey) throw std::runtime_error(args.plan + ": no storey '" + storey_name + "'");
  const auto truth_storey = static_cast<std::size_t>(storey - building.storeys.data());

  LocalizerSettings settings = args.config.empty() ? LocalizerSettings{} : loadLocalizerConfig(args.config);
  bimloc::LocalizerConfig config = settings.config;
  if (!args.method.empty()) config.method = *bimloc::methodFromString(args.method);
  config.seed = args.seed;
  config.storey = storey_auto || settings.storey_auto ? std::string() : storeyKey(building, truth_storey);
  bimloc::Localizer localizer(building, data.T_base_lidar, config);
  RunScore score(building, truth_storey);
  ScenarioResult r;
  r.name = args.dataset, r.plan = args.plan, r.storey = storey->name, r.method = bimloc::toString(config.method), r.seed = args.seed;
  r.storey_auto = config.storey.empty();
  r.start_room = "(unknown)";
  std::optional<bimloc::LocalizationResult> last;
  MapErrorSampler map_error(building);  // the scans placed with the estimate against the plan's mesh
  for (const auto& scan : data.scans) {
    const double t = scan.stamp_s + 0.5 * data.turn_period_s;  // mid-turn, as the runner
    // The scan's file is read only when the localizer looks at it, as the runner extracts planes.
    last = localizer.step(t, nearest(data.odometry, t).pose, [&scan] { return readPcdPoints(scan.file); });
    if (last->filter && last->filter->decided && !r.storey_margin && r.storey_auto) r.storey_margin = last->filter->storey_margin;
    for (const auto& w : last->warnings) r.warnings.push_back(scan.file + ": " + w);
    map_error.step(*last, data.T_base_lidar, [&scan] { return readPcdPoints(scan.file); });
    if (!data.ground_truth.empty()) score.add(t - data.scans.front().stamp_s, *last, nearest(data.ground_truth, t).pose);
  }
  if (data.ground_truth.empty()) {
    r.converged = last && last->convergence_stamp_s;
    if (last && last->storey) r.found_storey = building.storeys[*last->storey].name;
    r.losses = last ? last->losses : 0;
  } else {
    score.finish(r);
  }
  if (const auto* tracker = localizer.tracker())
    for (const auto& w : tracker->wallDeviations()) r.wall_deviations.push_back({w, std::nullopt, std::nullopt});
  r.map_rmse_m = map_error.rmse_m();
  r.sim_seconds = data.scans.empty() ? 0.0 : data.scans.back().stamp_s - data.scans.front().stamp_s + data.turn_period_s;
  r.wall_seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  r.passed = r.converged && !r.false_convergence;
  const auto report = bimloc::cli::runReport({r}, r.wall_seconds);
  if (args.json) {
    std::cout << report.dump() << "\n";
  } else {
    bimloc::cli::printRunTable({r}, report, std::cout);
    if (last && last->T_map_odom) {
      const Eigen::Isometry3d& T = *last->T_map_odom;
      const Eigen::Quaterniond q(T.linear());
      std::cout << "map <- odom: xyz " << T.translation().transpose() << ", quaternion xyzw " << q.x() << " " << q.y() << " "
                << q.z() << " " << q.w() << " (" << bimloc::toString(last->state) << ")\n";
    }
    if (data.ground_truth.empty()) std::cout << "(no ground_truth.tum: errors not evaluated)\n";
  }
  // As `run`: a run that did not localize, or localized falsely, fails.
  if (!r.passed) throw bimloc::cli::ExitCode{1};
}

}  // namespace

void addLocalizeCommand(CLI::App& app) {
  auto args = std::make_shared<LocalizeArgs>();
  CLI::App* cmd = app.add_subcommand(
      "localize",
      "Run the localizer offline on a dataset in the form `bimloc simulate` writes (clouds/*.pcd with\n"
      "clouds/index.csv, odometry.tum, metadata.json with the mount; ground_truth.tum if known) against a plan:\n"
      "global localization, then map <- odom. Scored like `bimloc run` when ground truth is present.");
  cmd->add_option("dataset", args->dataset, "dataset folder")->required();
  cmd->add_option("--plan", args->plan, "IFC plan")->required();
  cmd->add_option("--storey", args->storey,
                  "storey name or index (default: as recorded, else 0); auto: not told, every storey with walls and rooms "
                  "is a candidate (scored against the recorded storey)");
  cmd->add_option("--method", args->method,
                  bimloc::cli::kMethodHelp)
      ->check(bimloc::cli::methodCheck())
      ->capture_default_str();
  cmd->add_option("--config", args->config, "YAML file of localizer settings (the keys of a scenario's `localizer:`)")
      ->check(CLI::ExistingFile);
  cmd->add_option("--seed", args->seed, "seed of the filter")->capture_default_str();
  cmd->add_flag("--json", args->json, "print one JSON object");
  cmd->callback([args] { run(*args); });
}
