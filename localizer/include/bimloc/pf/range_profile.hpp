// A scan reduced to what free-space evidence needs (pf/free_space_evidence.hpp): per azimuth bin
// around the lidar, the farthest return at the heights where walls stand and most furniture does
// not. The farthest, because clutter only ever shortens a ray: what reaches farthest in a bin is
// the best view of the wall behind the desk, and a ray that reaches beyond a place's wall is
// evidence against that place whatever stood in front of it.
#pragma once

#include <Eigen/Core>
#include <Eigen/Geometry>

#include <vector>

namespace bimloc::pf {

struct RangeProfileConfig {
  // Heights above the floor (base_link's z, REP 105: the base stands on the floor). 1.0-1.8 m:
  // above desks, tables, chairs and kitchen counters (0.75-0.95 m), below door heads (2.0 m,
  // so rays through doorways are kept) and ceilings' bulkheads; people cross it, and are
  // bounded by the model (they only shorten rays).
  double min_height_m = 1.0;
  double max_height_m = 1.8;
  double bin_deg = 2.0;         // 180 bins: at 10 m a bin is 0.35 m wide, a doorway holds 2-3
  double min_range_m = 0.4;     // the robot's own body and mast
};

struct RangeProfile {
  Eigen::Vector3d origin_base = Eigen::Vector3d::Zero();  // the lidar's position, base frame
  // One end per non-empty bin: the farthest return's x y (base frame) and height above the floor.
  std::vector<Eigen::Vector3f> ends_base;
  // How far the turn's rays may be off the pose it is stamped with: a spinning lidar's turn
  // spans the interval between steps, and a robot turning at 60 deg/s turns 6 deg in it, so a
  // turn not de-skewed puts its first and last rays up to 3 deg (1 m at 20 m) off the
  // mid-turn pose. Half the odometry's heading and position change since the last step
  // (Localizer::step, setTurnSkew); for a de-skewed turn, the odometry's error over that half
  // (LocalizerConfig::points_deskewed); 0 for a standing robot.
  double skew_yaw_rad = 0.0;
  double skew_m = 0.0;
  bool empty() const { return ends_base.empty(); }
};

// points_lidar in the lidar frame, T_base_lidar the mount. At most 360 / bin_deg rays.
RangeProfile rangeProfile(const std::vector<Eigen::Vector3f>& points_lidar, const Eigen::Isometry3d& T_base_lidar,
                          const RangeProfileConfig& config);

}  // namespace bimloc::pf
