#include "sim/cli/trace_writer.hpp"

#include "sim/cli/snapshots.hpp"
#include "sim/dataset/tum_writer.hpp"
#include "sim/common/atomic_file.hpp"

#include <cmath>
#include <cstdio>
#include <filesystem>

namespace bimloc::cli {

std::string writeTrace(const std::string& dir, const std::string& scenario_name, const std::vector<sim::TraceRow>& rows) {
  std::filesystem::create_directories(dir);
  const std::string path = (std::filesystem::path(dir) / (fileSafe(scenario_name) + ".csv")).string();
  constexpr double kDeg = 180.0 / M_PI;
  // With storey auto, two more columns: the leading storey and its margin over the others.
  bool storeys = false;
  for (const auto& row : rows) storeys = storeys || !row.storey.empty();
  std::string csv =
      "time_s,truth_x_m,truth_y_m,truth_yaw_deg,estimate_x_m,estimate_y_m,estimate_yaw_deg,position_error_m,"
      "observations,associated,hypotheses,injected,ess,path_best_x_m,path_best_y_m,path_best_yaw_deg,path_margin,"
      "path_candidates,rival_x_m,rival_y_m,rival_yaw_deg,pose_margin,converged,places,goal_x_m,goal_y_m,goal_information,goal_walk_m";
  csv += storeys ? ",storey,storey_margin\n" : "\n";
  for (const auto& row : rows) {
    const auto& r = row.report;
    const Eigen::Vector3d best = r.path_best.value_or(Eigen::Vector3d::Constant(std::nan("")));
    // The closest rival (the place the margin is taken against), when one is within the bar;
    // pose_margin: the refined pose's margin within its place, when convergence was asked
    // (ParticleFilterConfig::settle_pose; nan otherwise).
    const Eigen::Vector3d rival = r.path_rivals.empty() ? Eigen::Vector3d::Constant(std::nan("")) : r.path_rivals.front().first;
    char line[512];
    std::snprintf(line, sizeof line, "%.2f,%.3f,%.3f,%.2f,%.3f,%.3f,%.2f,%.3f,%d,%d,%d,%d,%.1f,%.3f,%.3f,%.2f,%.2f,%d,%.3f,%.3f,%.2f,%.2f,%d,%zu,%.3f,%.3f,%.3f,%.2f",
                  row.time_s, row.truth.x(), row.truth.y(), row.truth.z() * kDeg, row.estimate.x(), row.estimate.y(),
                  row.estimate.z() * kDeg, (row.estimate - row.truth).head<2>().norm(), r.observations, r.associated,
                  r.hypotheses, r.injected, r.ess, best.x(), best.y(), best.z() * kDeg, r.path_margin, r.path_candidates,
                  rival.x(), rival.y(), rival.z() * kDeg, r.pose_margin, r.converged ? 1 : 0, row.places,
                  // The goal in the map as the best place has it (nan: none suggested).
                  row.goal ? row.goal->T_map_goal.front().x() : std::nan(""), row.goal ? row.goal->T_map_goal.front().y() : std::nan(""),
                  row.goal ? row.goal->information : std::nan(""), row.goal ? row.goal->walk_m : std::nan(""));
    csv += line;
    if (!storeys) {
      csv += "\n";
      continue;
    }
    std::string storey = row.storey;
    for (char& c : storey) c = c == ',' ? ';' : c;
    std::snprintf(line, sizeof line, ",%.2f\n", row.storey_margin.value_or(std::nan("")));
    csv += "," + storey + line;
  }
  sim::writeFileAtomically(path, csv);
  return path;
}

std::string writeTumPair(const std::string& dir, const std::string& scenario_name, const std::vector<sim::PoseRow>& rows) {
  const std::filesystem::path folder = std::filesystem::path(dir) / fileSafe(scenario_name);
  std::filesystem::create_directories(folder);
  std::string truth = "# " + scenario_name + ": true map <- base_link (timestamp tx ty tz qx qy qz qw)\n";
  std::string estimate = "# " + scenario_name + ": estimated map <- base_link, converged and not lost\n";
  for (const auto& row : rows) {
    const auto stamp_ns = static_cast<std::uint64_t>(std::llround(row.time_s * 1e9));
    truth += sim::tumLine(stamp_ns, row.truth) + "\n";
    if (row.scored) estimate += sim::tumLine(stamp_ns, row.estimate) + "\n";
  }
  sim::writeFileAtomically((folder / "truth.tum").string(), truth);
  sim::writeFileAtomically((folder / "estimate.tum").string(), estimate);
  return folder.string();
}

}  // namespace bimloc::cli
