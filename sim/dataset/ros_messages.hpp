// The ROS messages both bag writers build (the simulator's dataset.bag, localize's
// localized.bag): headers, poses and transforms from Eigen, rotations as canonicalRotation()
// (w >= 0, the same quaternion the TUM files carry).
#pragma once

#include <geometry_msgs/Pose.h>
#include <geometry_msgs/TransformStamped.h>
#include <ros/time.h>
#include <std_msgs/Header.h>

#include <Eigen/Geometry>
#include <cstdint>
#include <string>

namespace bimloc::sim {

ros::Time rosTime(std::uint64_t stamp_ns);
std_msgs::Header header(const ros::Time& stamp, std::uint32_t seq, const std::string& frame_id);
geometry_msgs::Pose poseMessage(const Eigen::Isometry3d& T);
// parent <- child at `stamp` (header seq 0, as tf2 publishes).
geometry_msgs::TransformStamped transformMessage(const ros::Time& stamp, const std::string& parent, const std::string& child,
                                                 const Eigen::Isometry3d& T_parent_child);

}  // namespace bimloc::sim
