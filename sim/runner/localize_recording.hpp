// The loop of `bimloc localize`, one for every kind of recording (a dataset folder, a ROS1
// bag): each lidar turn, in order, goes to Localizer::step with the odometry at its stamp,
// and the run is scored as `bimloc run` scores it when the recording has ground truth.
#pragma once

#include "sim/dataset/dataset_reader.hpp"
#include "sim/runner/run_scenario.hpp"

#include <bimloc/localizer.hpp>

#include <functional>
#include <string>
#include <vector>

namespace bimloc::sim {

struct RecordedTurn {
  double stamp_s = 0;  // the stamp the localizer is given (mid-turn)
  Eigen::Isometry3d T_odom_base = Eigen::Isometry3d::Identity();
  Localizer::PointSource points;  // in the lidar frame; called at most once per turn
  std::string name;               // for warnings: the PCD's path, the bag message
  // What the reader dropped of this scan (`points` gives the rest); no usable point: the turn
  // is skipped, never given to the localizer.
  PointDrops drops;
  std::vector<std::string> warnings;  // the reader's, about this scan (its layout)
};

// Calls its argument for each turn, in order.
using TurnSource = std::function<void(const std::function<void(const RecordedTurn&)>&)>;
// After each step (to write outputs: trajectory, bag, snapshots).
using TurnObserver = std::function<void(const RecordedTurn&, const LocalizationResult&)>;

struct RecordingRun {
  ScenarioResult result;  // scored when `truth` is not empty; `passed` set
  std::optional<LocalizationResult> last;
};

// Turns with no usable point are skipped; result.recording counts the scans and points
// dropped (its odometry part is the caller's). Throws std::runtime_error when no turn at all
// has a usable point: the recording cannot be used.
// `start_s`: the recording's start (errors are timed from it, as `run` times them from the
// simulation's start). `result` carries the run's names (name, plan, storey, method, seed, storey_auto) and is
// completed. `truth` (map <- base_link) may be empty: then nothing is scored but convergence.
RecordingRun localizeRecording(const bim::Building& building, std::size_t truth_storey, Localizer& localizer,
                               const Eigen::Isometry3d& T_base_lidar, const TurnSource& turns, double start_s,
                               const std::vector<StampedPose>& truth, ScenarioResult result,
                               const TurnObserver& observe = {});

}  // namespace bimloc::sim
