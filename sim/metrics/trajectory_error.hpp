// APE and RPE of an estimated trajectory against the truth, the way evo computes them
// (evo_ape / evo_rpe with the translation part, Z. Zhang and D. Scaramuzza, "A Tutorial on
// Quantitative Trajectory Evaluation for Visual(-Inertial) Odometry", IROS 2018; Sturm et al.,
// "A Benchmark for the Evaluation of RGB-D SLAM Systems", IROS 2012, for the RPE):
//   1. associate the poses by timestamp (sim/metrics/trajectory_sync.hpp),
//   2. align the estimate on the truth (Umeyama, SE(3) or Sim(3)), or not,
//   3. optionally project both onto the xy plane (evo's --project_to_plane xy),
//   4. APE_i = |p_est_i - p_ref_i|; RPE over pose pairs (i, j) every `delta` frames or metres
//      of path, chosen on the (aligned) estimate as evo does by default, or on the truth (evo's
//      --pairs_from_reference): |trans((Q_i^-1 Q_j)^-1 (P_i^-1 P_j))|, Q the truth, P the estimate.
#pragma once

#include "sim/dataset/tum_reader.hpp"
#include "sim/metrics/umeyama.hpp"

#include <optional>
#include <string>
#include <utility>
#include <vector>

namespace bimloc::sim {

// As evo's metrics.get_all_statistics: rmse, mean, median (the mean of the middle two for an
// even count), std (population: divided by n), min, max, sse (sum of squares).
struct ErrorStatistics {
  std::size_t count = 0;
  double rmse = 0, mean = 0, median = 0, std = 0, min = 0, max = 0, sse = 0;
};
ErrorStatistics errorStatistics(const std::vector<double>& errors);  // throws std::invalid_argument when empty

enum class TrajectoryAlignment { None, SE3, SE3Scale };

struct TrajectoryEvalOptions {
  TrajectoryAlignment align = TrajectoryAlignment::None;
  double max_diff_s = 0.01;    // evo's --t_max_diff
  double delta = 1.0;          // RPE: pairs this far apart ...
  bool delta_metres = false;   // ... in frames (false) or metres of path
  bool pairs_from_truth = false;  // the path that picks the pairs: the estimate's (evo's default) or the truth's
  bool project_xy = false;     // evo's --project_to_plane xy, after the alignment
};

struct TrajectoryEvaluation {
  std::size_t truth_poses = 0, estimate_poses = 0;
  Similarity alignment;                              // estimate -> truth (identity for None)
  std::vector<double> stamps_s;                      // of the associated estimate poses
  std::vector<Eigen::Isometry3d> truth, estimate;    // associated; the estimate aligned (and projected)
  std::vector<double> ape_m, ape_rotation_deg;       // per associated pose
  std::vector<std::pair<std::size_t, std::size_t>> rpe_pairs;  // indices into the associated poses
  std::vector<double> rpe_m;                         // per pair
  ErrorStatistics ape;
  // Unset when delta gives no pose pair (too few poses, too short a path): the APE stands,
  // and `warnings` says why there is no RPE.
  std::optional<ErrorStatistics> rpe;
  std::vector<std::string> warnings;
};

// Throws std::invalid_argument naming both files when no stamps match or when the alignment
// is not possible.
TrajectoryEvaluation evaluateTrajectory(const TumTrajectory& truth, const TumTrajectory& estimate,
                                        const TrajectoryEvalOptions& options);

}  // namespace bimloc::sim
