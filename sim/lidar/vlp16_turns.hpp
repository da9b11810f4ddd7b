// A stream of decoded VLP-16 points cut into turns, as a driver cuts its clouds: a turn ends
// where the azimuth passes the cut angle (nebula's scan_phase, velodyne_pointcloud's
// cut_angle; 0 deg, straight ahead, by default).
#pragma once

#include "sim/lidar/vlp16_packet.hpp"

#include <vector>

namespace bimloc::sim {

// The points in stream order, split where the azimuth relative to `cut_deg` falls back by
// more than half a turn. The first and last turns may be partial.
std::vector<std::vector<Vlp16Point>> splitVlp16Turns(const std::vector<Vlp16Point>& points, double cut_deg = 0.0);

}  // namespace bimloc::sim
