#include "sim/dataset/deskew.hpp"

#include <algorithm>
#include <cmath>

namespace bimloc::sim {

Eigen::Isometry3d interpolatePose(const std::vector<StampedPose>& samples, double t) {
  const auto after =
      std::lower_bound(samples.begin(), samples.end(), t, [](const StampedPose& s, double v) { return s.stamp_s < v; });
  if (after == samples.begin()) return samples.front().pose;
  if (after == samples.end()) return samples.back().pose;
  const StampedPose& a = *std::prev(after);
  const StampedPose& b = *after;
  const double f = (t - a.stamp_s) / (b.stamp_s - a.stamp_s);
  Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
  T.translation() = (1 - f) * a.pose.translation() + f * b.pose.translation();
  T.linear() = Eigen::Quaterniond(a.pose.linear()).slerp(f, Eigen::Quaterniond(b.pose.linear())).toRotationMatrix();
  return T;
}

void deskew(std::vector<Eigen::Vector3f>& points, const std::vector<double>& time_s, double stamp_s, double reference_s,
            const std::vector<StampedPose>& odometry, const Eigen::Isometry3d& T_base_lidar) {
  if (odometry.empty() || time_s.size() != points.size()) return;
  const Eigen::Isometry3d T_ref_odom = (interpolatePose(odometry, reference_s) * T_base_lidar).inverse();
  // The driver gives the points of one firing the same time: one transform per distinct time.
  double cached_time = std::nan("");
  Eigen::Isometry3f T_ref_point = Eigen::Isometry3f::Identity();
  for (std::size_t i = 0; i < points.size(); ++i) {
    if (!(time_s[i] == cached_time)) {
      cached_time = time_s[i];
      T_ref_point = (T_ref_odom * interpolatePose(odometry, stamp_s + time_s[i]) * T_base_lidar).cast<float>();
    }
    points[i] = T_ref_point * points[i];
  }
}

std::vector<Eigen::Vector3f> deskewedTurn(const LidarScan& scan, const std::vector<StampedPose>& odometry, double reference_s,
                                          const Eigen::Isometry3d& T_base_lidar) {
  std::vector<Eigen::Vector3f> points;
  points.reserve(scan.points.size());
  for (const auto& p : scan.points) points.emplace_back(p.x, p.y, p.z);
  if (odometry.empty()) return points;
  std::vector<double> time_s;
  time_s.reserve(scan.points.size());
  for (const auto& p : scan.points) time_s.push_back(p.time);
  deskew(points, time_s, scan.stamp_s, reference_s, odometry, T_base_lidar);
  return points;
}

}  // namespace bimloc::sim
