// A lidar turn as the ROS velodyne driver publishes it (sensor_msgs/PointCloud2 fields
// x, y, z, intensity, ring, time), in the sensor frame "velodyne".
#pragma once

#include <cstdint>
#include <string>
#include <vector>

namespace bimloc::sim {

struct LidarPoint {
  float x = 0, y = 0, z = 0;  // metres, sensor frame at the point's own firing instant
  float intensity = 0;        // 0..255, from the incidence angle
  std::uint16_t ring = 0;     // 0 = lowest beam (-15 deg), as Gazebo's and the driver's convention
  float time = 0;             // seconds since the turn's first firing
};

struct LidarScan {
  double stamp_s = 0.0;  // time of the turn's first firing (the driver stamps the turn's start)
  std::string frame_id = "velodyne";
  std::vector<LidarPoint> points;
};

}  // namespace bimloc::sim
