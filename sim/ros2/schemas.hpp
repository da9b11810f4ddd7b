// The ros2msg definitions of the messages bimloc writes, as an MCAP Schema record carries them
// (rosbag2's docs/message_definition_encoding.md): the type's .msg text, then each type it
// uses after a line of 80 '=' and "MSG: pkg/Type". Readers such as Foxglove decode the
// CDR by this text, so it must match messages.cpp field for field.
#pragma once

#include <string>

namespace bimloc::sim::ros2 {

// "sensor_msgs/msg/PointCloud2", "nav_msgs/msg/Odometry", "tf2_msgs/msg/TFMessage",
// "geometry_msgs/msg/PoseStamped", "geometry_msgs/msg/PoseWithCovarianceStamped",
// "visualization_msgs/msg/MarkerArray", "velodyne_msgs/msg/VelodyneScan". Throws std::invalid_argument for another type.
std::string ros2msgDefinition(const std::string& type);

}  // namespace bimloc::sim::ros2
