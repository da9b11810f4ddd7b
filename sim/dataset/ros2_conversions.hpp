// ROS 2 messages from Eigen, for both ROS 2 writers (the simulator's rosbag2/, localize's
// localized.mcap): rotations as canonicalRotation() (w >= 0), as the ROS 1 bag and TUM files.
#pragma once

#include "sim/ros2/messages.hpp"

#include <Eigen/Geometry>

#include <cstdint>
#include <string>

namespace bimloc::sim {

ros2::Pose ros2Pose(const Eigen::Isometry3d& T);
// parent <- child at `stamp_ns`.
ros2::TransformStamped ros2Transform(std::uint64_t stamp_ns, const std::string& parent, const std::string& child,
                                     const Eigen::Isometry3d& T_parent_child);

}  // namespace bimloc::sim
