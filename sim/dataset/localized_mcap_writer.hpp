// localized.mcap of `bimloc localize` on a ROS 2 bag: what localized.bag is for a ROS 1 bag
// (every message of the input, /tf map -> odom, /localization as PoseWithCovarianceStamped),
// plus the plan once on /bimloc/plan (visualization_msgs/msg/MarkerArray: the storey's walls
// and rooms, latched: transient_local in the channel's QoS), so Foxglove or RViz 2 shows the
// robot in the building. Written in log-time order when closed (the input is read again then).
#pragma once

#include <bimloc/bim/building.hpp>

#include <Eigen/Core>
#include <Eigen/Geometry>

#include <memory>
#include <string>
#include <vector>

namespace bimloc::sim {

inline constexpr const char* kPlanTopic = "/bimloc/plan";

class LocalizedMcapWriter {
 public:
  // Creates `path`; throws std::runtime_error naming it.
  LocalizedMcapWriter(const std::string& path, const std::string& input_bag, std::string map_frame, std::string odom_frame,
                      std::string base_frame, std::string tf_topic);
  ~LocalizedMcapWriter();
  LocalizedMcapWriter(const LocalizedMcapWriter&) = delete;
  LocalizedMcapWriter& operator=(const LocalizedMcapWriter&) = delete;

  void add(double stamp_s, const Eigen::Isometry3d& T_map_odom, const Eigen::Isometry3d& T_map_base,
           const Eigen::Matrix3d& covariance_xy_yaw);
  // `storey`: the plan's storey drawn on /bimloc/plan (the one localized in).
  void close(const bim::Storey& storey);

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace bimloc::sim
