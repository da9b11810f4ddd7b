#include "peers/amcl/scan.hpp"

#include <bimloc/geometry/planar_pose.hpp>

#include <algorithm>
#include <cmath>
#include <limits>

namespace bimloc::peers::amcl {

LaserScan projectScan(const std::vector<Eigen::Vector3f>& points_lidar, const Eigen::Isometry3d& T_base_lidar,
                      const Eigen::Isometry3d& T_odom_base, const AmclConfig& config) {
  LaserScan scan;
  scan.increment = config.scan_angle_increment_deg * M_PI / 180.0;
  const int count = std::max(1, static_cast<int>(std::lround(2.0 * M_PI / scan.increment)));
  scan.ranges.assign(count, std::numeric_limits<double>::infinity());
  scan.ends.assign(count, Eigen::Vector2d::Zero());
  scan.points = static_cast<int>(points_lidar.size());
  // Levelled base frame: the base's heading, no roll or pitch, origin at the base.
  const Eigen::Matrix3d tilt = tiltOf(T_odom_base.linear());
  const Eigen::Matrix3d R = tilt * T_base_lidar.linear();
  const Eigen::Vector3d t = tilt * T_base_lidar.translation();
  const double base_height = T_odom_base.translation().z();
  for (const auto& pf : points_lidar) {
    if (!pf.allFinite()) {
      ++scan.non_finite;
      continue;
    }
    const Eigen::Vector3d p = R * pf.cast<double>() + t;
    const double height = base_height + p.z();
    if (height < config.band_min_m || height > config.band_max_m) continue;
    const double range = std::hypot(p.x(), p.y());
    if (range < config.laser_min_range_m || range > config.laser_max_range_m) continue;
    const double bearing = std::atan2(p.y(), p.x());
    const int beam = std::clamp(static_cast<int>(std::floor((bearing - scan.angle_min) / scan.increment)), 0, count - 1);
    if (range < scan.ranges[beam]) scan.ranges[beam] = range, scan.ends[beam] = p.head<2>();
    ++scan.in_band;
  }
  return scan;
}

std::vector<Eigen::Vector2d> selectBeams(const LaserScan& scan, int max_beams) {
  const int count = static_cast<int>(scan.ranges.size());
  const int step = max_beams > 1 ? std::max(1, (count - 1) / (max_beams - 1)) : std::max(1, count);
  std::vector<Eigen::Vector2d> beams;
  for (int i = 0; i < count; i += step) {
    if (!std::isfinite(scan.ranges[i])) continue;  // "This model ignores max range readings"
    beams.push_back(scan.ends[i]);
  }
  return beams;
}

}  // namespace bimloc::peers::amcl
