// What `bimloc localize --out DIR` writes, all of it or nothing (one StagingDirectory):
//   trajectory.tum  map <- base_link at every turn once localized (TUM: evo_ape tum ...)
//   localized.bag   (ROS 1 bag input only) the input plus /tf map -> odom and /localization
//   localized.mcap  (ROS 2 bag input only) the same, plus the plan on /bimloc/plan
//   report.json     the report `localize --json` prints, with "format": "bimloc.localize"
//   snapshots/      top views at convergence and at the end; errors.png with ground truth
#pragma once

#include "sim/runner/localize_recording.hpp"
#include "sim/common/atomic_file.hpp"

#include <nlohmann/json.hpp>

#include <memory>
#include <optional>
#include <string>

namespace bimloc::sim {
class LocalizedBagWriter;
class LocalizedMcapWriter;
class TumWriter;
}  // namespace bimloc::sim

namespace bimloc::cli {

struct LocalizeOutputFrames {
  std::string map = "map", odom = "odom", base = "base_link", tf_topic = "/tf";
};

class LocalizeOutput {
 public:
  // `input_bag`: the bag to copy into localized.bag (ROS 1) or localized.mcap (ROS 2), empty
  // for a dataset folder. The building
  // and the localizer must outlive this.
  LocalizeOutput(const std::string& dir, const std::string& input_bag, const LocalizeOutputFrames& frames,
                 const bim::Building& building, const Localizer& localizer);
  ~LocalizeOutput();

  // After each step. `truth`, when known, is drawn in the snapshots.
  void step(const sim::RecordedTurn& turn, const LocalizationResult& result, const std::optional<Eigen::Isometry3d>& truth);
  // Writes report.json, the last snapshot and the error plot, and puts DIR in place.
  void commit(const nlohmann::json& report, const sim::ScenarioResult& result);

 private:
  void snapshot(const std::string& phase, double time_s, const LocalizationResult& result,
                const std::optional<Eigen::Isometry3d>& truth);

  sim::StagingDirectory staging_;
  const bim::Building& building_;
  const Localizer& localizer_;
  std::unique_ptr<sim::TumWriter> trajectory_;
  std::unique_ptr<sim::LocalizedBagWriter> bag_;
  std::unique_ptr<sim::LocalizedMcapWriter> mcap_;
  std::optional<double> start_s_;
  bool converged_ = false;
  int snapshots_ = 0;
  std::optional<LocalizationResult> last_;
  std::optional<Eigen::Isometry3d> last_truth_;
};

}  // namespace bimloc::cli
