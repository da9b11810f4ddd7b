// One lidar turn as a binary PCD file (PCL's format v0.7), written without PCL.
#pragma once

#include "sim/lidar/lidar_scan.hpp"

#include <string>

namespace bimloc::sim {

// The header (FIELDS x y z intensity ring time, one point per column, HEIGHT 1) followed by
// the points in the velodyne driver's packed 22-byte layout. Throws std::runtime_error
// naming the path.
std::string pcdHeader(std::size_t point_count);
void writePcd(const std::string& path, const std::vector<LidarPoint>& points);

}  // namespace bimloc::sim
