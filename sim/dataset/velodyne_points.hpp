// The point layout of the ROS velodyne driver's clouds, shared by the bag and the PCD files.
#pragma once

#include "sim/lidar/lidar_scan.hpp"

#include <array>
#include <cstdint>
#include <vector>

namespace bimloc::sim {

enum class PointFieldType : std::uint8_t { kFloat32, kUint16 };

struct PointFieldLayout {
  const char* name;
  std::uint32_t offset_bytes;
  std::uint32_t size_bytes;
  PointFieldType type;
};

// What velodyne_pointcloud's PointcloudXYZIRT publishes (ros-drivers/velodyne,
// DataContainerBase): x, y, z, intensity as FLOAT32, ring as UINT16, time as FLOAT32, placed
// one after the other by sensor_msgs' addPointField, which adds no padding: offsets
// 0, 4, 8, 12, 16, 18 and a point_step of 22. The 32-byte, 16-aligned PointXYZIRT is only
// the PCL struct that consumers (LIO-SAM...) convert into by field name, never the wire
// layout, so a reader that works on the driver's bags works on ours. `time` at offset 18 is
// unaligned: readers must copy, not cast.
inline constexpr std::uint32_t kVelodynePointStepBytes = 22;
const std::array<PointFieldLayout, 6>& velodynePointFields();

// Whether this machine stores numbers least significant byte first (x86, ARM as run).
bool hostIsLittleEndian();

// The points packed in that layout, little-endian (as ROS and PCD binary on x86/ARM).
std::vector<std::uint8_t> packVelodynePoints(const std::vector<LidarPoint>& points);

}  // namespace bimloc::sim
