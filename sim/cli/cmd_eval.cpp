// bimloc eval TRUTH.tum ESTIMATE.tum [--align none|se3|se3-scale] [--delta 1] [--delta-unit frames|m]
//             [--max-diff 0.01] [--project xy] [--json] [--plot FILE.png]
// APE and RPE (translation part) as evo_ape / evo_rpe report them (sim/metrics/trajectory_error.hpp).
#include "sim/cli/commands.hpp"
#include "sim/cli/table.hpp"
#include "sim/metrics/trajectory_error.hpp"
#include "sim/render/trajectory_plot.hpp"

#include <nlohmann/json.hpp>

#include <iostream>
#include <sstream>

namespace {

using namespace bimloc::sim;
using bimloc::cli::fixed;

struct EvalArgs {
  std::string truth, estimate, align = "none", delta_unit = "frames", project, plot;
  double delta = 1, max_diff_s = 0.01;
  bool json = false, pairs_from_truth = false;
};

nlohmann::json statsJson(const ErrorStatistics& s) {
  return {{"count", s.count}, {"rmse", s.rmse}, {"mean", s.mean}, {"median", s.median}, {"std", s.std},
          {"min", s.min},     {"max", s.max},   {"sse", s.sse}};
}

std::vector<std::string> statsRow(const std::string& name, const ErrorStatistics& s) {
  return {name, std::to_string(s.count), fixed(s.rmse, 4), fixed(s.mean, 4), fixed(s.median, 4), fixed(s.std, 4),
          fixed(s.min, 4), fixed(s.max, 4), fixed(s.sse, 4)};
}

void evaluate(const EvalArgs& args) {
  const TumTrajectory truth = readTum(args.truth), estimate = readTum(args.estimate);
  TrajectoryEvalOptions o;
  o.align = args.align == "se3" ? TrajectoryAlignment::SE3 : args.align == "se3-scale" ? TrajectoryAlignment::SE3Scale : TrajectoryAlignment::None;
  o.max_diff_s = args.max_diff_s;
  o.delta = args.delta;
  o.delta_metres = args.delta_unit == "m";
  o.project_xy = args.project == "xy";
  o.pairs_from_truth = args.pairs_from_truth;
  const TrajectoryEvaluation e = evaluateTrajectory(truth, estimate, o);
  std::vector<std::string> warnings = truth.warnings;
  warnings.insert(warnings.end(), estimate.warnings.begin(), estimate.warnings.end());
  warnings.insert(warnings.end(), e.warnings.begin(), e.warnings.end());
  for (const auto& w : warnings) std::cerr << "bimloc eval: warning: " << w << "\n";

  if (!args.plot.empty()) {
    TrajectoryPlotData plot;
    plot.title = "APE " + fixed(e.ape.rmse, 3) + " m RMSE, align " + args.align + ": " + args.estimate;
    for (std::size_t i = 0; i < e.truth.size(); ++i) {
      plot.truth.push_back(e.truth[i].translation().head<2>());
      plot.estimate.push_back(e.estimate[i].translation().head<2>());
      plot.time_s.push_back(e.stamps_s[i] - e.stamps_s.front());
    }
    plot.ape_m = e.ape_m, plot.ape_rotation_deg = e.ape_rotation_deg;
    renderTrajectoryPlot(plot, args.plot);
  }

  const Eigen::Matrix3d& r = e.alignment.rotation;
  const Eigen::Vector3d& t = e.alignment.translation;
  if (args.json) {
    nlohmann::json j = {
        {"truth", args.truth}, {"estimate", args.estimate},
        {"poses", {{"truth", e.truth_poses}, {"estimate", e.estimate_poses}, {"associated", e.truth.size()}}},
        {"max_diff_s", args.max_diff_s}, {"align", args.align}, {"project", args.project.empty() ? nlohmann::json(nullptr) : nlohmann::json(args.project)},
        {"alignment", {{"rotation", {{r(0, 0), r(0, 1), r(0, 2)}, {r(1, 0), r(1, 1), r(1, 2)}, {r(2, 0), r(2, 1), r(2, 2)}}},
                       {"translation", {t.x(), t.y(), t.z()}}, {"scale", e.alignment.scale}}},
        {"ape", {{"unit", "m"}, {"relation", "translation part"}, {"statistics", statsJson(e.ape)}}},
        {"rpe", {{"unit", "m"}, {"relation", "translation part"}, {"delta", args.delta}, {"delta_unit", args.delta_unit},
                 {"pairs_from", args.pairs_from_truth ? "truth" : "estimate"},
                 {"statistics", e.rpe ? statsJson(*e.rpe) : nlohmann::json(nullptr)}}},
        {"warnings", warnings}};
    std::cout << j.dump() << "\n";
    return;
  }
  // Two sentences, each broken to the table's width (the paths may be long).
  std::ostringstream head, how;
  head << "truth " << args.truth << " (" << e.truth_poses << " poses), estimate " << args.estimate << " (" << e.estimate_poses
       << " poses): " << e.truth.size() << " associated (max. time difference " << args.max_diff_s << " s)";
  if (o.align == TrajectoryAlignment::None)
    how << "not aligned";
  else
    how << (o.align == TrajectoryAlignment::SE3 ? "SE(3)" : "Sim(3)") << " Umeyama alignment: translation (" << fixed(t.x(), 4)
        << ", " << fixed(t.y(), 4) << ", " << fixed(t.z(), 4) << ") m, rotation "
        << fixed(Eigen::AngleAxisd(r).angle() * 180.0 / M_PI, 3) << " deg, scale " << fixed(e.alignment.scale, 6);
  if (o.project_xy) how << ", projected to the xy plane";
  std::cout << bimloc::cli::wrapText(head.str(), bimloc::cli::kTableColumns) << bimloc::cli::wrapText(how.str(), bimloc::cli::kTableColumns)
            << "\n";
  bimloc::cli::Table table({"metric [m]", "n", "rmse", "mean", "median", "std", "min", "max", "sse"});
  table.add(statsRow("APE translation", e.ape));
  const std::string rpe_name = "RPE translation, delta " + fixed(args.delta, args.delta_unit == "m" ? 2 : 0) + " " + args.delta_unit;
  if (e.rpe)
    table.add(statsRow(rpe_name, *e.rpe));
  else
    table.add({rpe_name, "0", "-", "-", "-", "-", "-", "-", "-"});
  table.print(std::cout);
  if (!args.plot.empty()) std::cout << "\nplot: " << args.plot << "\n";
}

}  // namespace

void addEvalCommand(CLI::App& app) {
  auto args = std::make_shared<EvalArgs>();
  CLI::App* cmd = app.add_subcommand(
      "eval",
      "Evaluate an estimated trajectory against the truth, both in the TUM format (timestamp tx ty tz qx qy qz qw),\n"
      "as evo_ape / evo_rpe do: poses associated by timestamp (evo's associate_trajectories), the estimate aligned\n"
      "(Umeyama: se3, or se3-scale for Sim(3)) or not, then APE and RPE of the translation part: rmse, mean,\n"
      "median, std, min, max, sse. `bimloc run --tum DIR` writes a run's truth.tum and estimate.tum.");
  cmd->add_option("truth", args->truth, "reference trajectory (TUM)")->required();
  cmd->add_option("estimate", args->estimate, "estimated trajectory (TUM)")->required();
  cmd->add_option("--align", args->align, "none, se3 (evo -a) or se3-scale (evo -as)")
      ->check(CLI::IsMember({"none", "se3", "se3-scale"}))
      ->capture_default_str();
  cmd->add_option("--delta", args->delta, "RPE: pose pairs this far apart (evo --delta)")->capture_default_str();
  cmd->add_option("--delta-unit", args->delta_unit, "frames or m (metres of path; evo --delta_unit f|m)")
      ->check(CLI::IsMember({"frames", "m"}))
      ->capture_default_str();
  cmd->add_flag("--pairs-from-truth", args->pairs_from_truth,
                "RPE: pick the pose pairs on the truth's path, not the estimate's (evo --pairs_from_reference)");
  cmd->add_option("--max-diff", args->max_diff_s, "largest time difference [s] of associated poses (evo --t_max_diff)")
      ->check(CLI::Range(0.0, 1e9))
      ->capture_default_str();
  cmd->add_option("--project", args->project, "xy: project both onto the plane after the alignment (evo --project_to_plane xy)")
      ->check(CLI::IsMember({"xy"}));
  cmd->add_flag("--json", args->json, "print one JSON object instead of the table");
  cmd->add_option("--plot", args->plot, "PNG of both trajectories from above and the error over time");
  cmd->callback([args] { evaluate(*args); });
}
