#include "sim/metrics/trajectory_error.hpp"

#include "sim/metrics/trajectory_sync.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <numeric>
#include <stdexcept>

namespace bimloc::sim {

namespace {

std::string text(double v) {
  char b[32];
  std::snprintf(b, sizeof b, "%g", v);
  return b;
}

// evo's Trajectory.project(Plane.XY): z dropped, the rotation reduced to its yaw (the z angle
// of the static x-y-z Euler angles).
Eigen::Isometry3d projectXy(const Eigen::Isometry3d& pose) {
  Eigen::Isometry3d out = Eigen::Isometry3d::Identity();
  const Eigen::Matrix3d& r = pose.linear();
  out.linear() = Eigen::AngleAxisd(std::atan2(r(1, 0), r(0, 0)), Eigen::Vector3d::UnitZ()).toRotationMatrix();
  out.translation() = Eigen::Vector3d(pose.translation().x(), pose.translation().y(), 0.0);
  return out;
}

// evo's filters.filter_pairs_by_index and filter_pairs_by_path (consecutive pairs, not all
// pairs): by path, a pose is a pair's end once the path since the previous end reaches delta,
// the first one included (so the first pair starts there, not at pose 0, as in evo).
std::vector<std::pair<std::size_t, std::size_t>> rpePairs(const std::vector<Eigen::Isometry3d>& poses, double delta, bool metres) {
  std::vector<std::size_t> ids;
  if (!metres) {
    for (std::size_t i = 0; i < poses.size(); i += static_cast<std::size_t>(delta)) ids.push_back(i);
  } else {
    double path = 0;
    for (std::size_t i = 0; i < poses.size(); ++i) {
      if (i > 0) path += (poses[i].translation() - poses[i - 1].translation()).norm();
      if (path >= delta) ids.push_back(i), path = 0;
    }
  }
  std::vector<std::pair<std::size_t, std::size_t>> pairs;
  for (std::size_t k = 1; k < ids.size(); ++k) pairs.emplace_back(ids[k - 1], ids[k]);
  return pairs;
}

}  // namespace

ErrorStatistics errorStatistics(const std::vector<double>& errors) {
  if (errors.empty()) throw std::invalid_argument("no errors to summarise");
  ErrorStatistics s;
  s.count = errors.size();
  const auto n = static_cast<double>(errors.size());
  for (const double e : errors) s.sse += e * e;
  s.mean = std::accumulate(errors.begin(), errors.end(), 0.0) / n;
  s.rmse = std::sqrt(s.sse / n);
  double var = 0;
  for (const double e : errors) var += (e - s.mean) * (e - s.mean);
  s.std = std::sqrt(var / n);
  std::vector<double> sorted = errors;
  std::sort(sorted.begin(), sorted.end());
  const std::size_t m = sorted.size() / 2;
  s.median = sorted.size() % 2 ? sorted[m] : 0.5 * (sorted[m - 1] + sorted[m]);
  s.min = sorted.front();
  s.max = sorted.back();
  return s;
}

TrajectoryEvaluation evaluateTrajectory(const TumTrajectory& truth, const TumTrajectory& estimate,
                                        const TrajectoryEvalOptions& options) {
  const std::string files = truth.path + " and " + estimate.path;
  if (options.delta_metres ? !(options.delta > 0) : !(options.delta >= 1 && std::floor(options.delta) == options.delta))
    throw std::invalid_argument("RPE delta " + text(options.delta) + (options.delta_metres ? " m: must be > 0" : " frames: must be a whole number >= 1"));
  TrajectoryEvaluation e;
  e.truth_poses = truth.poses.size();
  e.estimate_poses = estimate.poses.size();
  const StampPairs pairs = associateStamps(truth.stamps_s, estimate.stamps_s, options.max_diff_s);
  if (pairs.first.empty())
    throw std::invalid_argument("no matching timestamps between " + files + " with max. time difference " +
                                text(options.max_diff_s) + " s (truth " + text(truth.stamps_s.front()) + " to " +
                                text(truth.stamps_s.back()) + " s, estimate " + text(estimate.stamps_s.front()) + " to " +
                                text(estimate.stamps_s.back()) + " s)");
  const std::size_t n = pairs.first.size();
  Eigen::Matrix3Xd from(3, n), to(3, n);
  for (std::size_t k = 0; k < n; ++k) {
    e.truth.push_back(truth.poses[pairs.first[k]]);
    e.estimate.push_back(estimate.poses[pairs.second[k]]);
    e.stamps_s.push_back(estimate.stamps_s[pairs.second[k]]);
    from.col(static_cast<Eigen::Index>(k)) = e.estimate.back().translation();
    to.col(static_cast<Eigen::Index>(k)) = e.truth.back().translation();
  }
  if (options.align != TrajectoryAlignment::None) {
    try {
      e.alignment = umeyama(from, to, options.align == TrajectoryAlignment::SE3Scale);
    } catch (const std::invalid_argument& error) {
      throw std::invalid_argument(files + ": " + error.what());
    }
    for (auto& p : e.estimate) {  // evo: scale the positions, then transform the poses
      p.translation() = e.alignment.apply(p.translation());
      p.linear() = e.alignment.rotation * p.linear();
    }
  }
  if (options.project_xy) {
    for (auto& p : e.truth) p = projectXy(p);
    for (auto& p : e.estimate) p = projectXy(p);
  }
  for (std::size_t k = 0; k < n; ++k) {
    e.ape_m.push_back((e.estimate[k].translation() - e.truth[k].translation()).norm());
    const Eigen::AngleAxisd d(e.truth[k].linear().transpose() * e.estimate[k].linear());
    e.ape_rotation_deg.push_back(std::abs(d.angle()) * 180.0 / M_PI);
  }
  e.ape = errorStatistics(e.ape_m);
  e.rpe_pairs = rpePairs(options.pairs_from_truth ? e.truth : e.estimate, options.delta, options.delta_metres);
  if (e.rpe_pairs.empty()) {
    e.warnings.push_back("no RPE: delta " + text(options.delta) + (options.delta_metres ? " m" : " frames") +
                         " gives no pose pair among the " + std::to_string(n) + " associated poses of " + files +
                         " (try a lower --delta)");
    return e;
  }
  for (const auto& [i, j] : e.rpe_pairs) {
    const Eigen::Isometry3d q = e.truth[i].inverse() * e.truth[j], p = e.estimate[i].inverse() * e.estimate[j];
    e.rpe_m.push_back((q.inverse() * p).translation().norm());
  }
  e.rpe = errorStatistics(e.rpe_m);
  return e;
}

}  // namespace bimloc::sim
