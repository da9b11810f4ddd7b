// velodyne_msgs/msg/VelodyneScan of a ROS 2 bag, read from its CDR bytes (sim/ros2/cdr.hpp):
// std_msgs/Header, then VelodynePacket[] of {builtin_interfaces/Time stamp; uint8[1206] data}.
// The packets point into the message: use them while it lives.
#pragma once

#include "sim/dataset/velodyne_scan_points.hpp"

#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

namespace bimloc::sim {

namespace ros2 {
class CdrReader;
}

struct VelodyneScanView {
  double header_s = 0;
  std::string frame_id;
  std::vector<RawPacket> packets;
};

// Throws std::runtime_error "WHERE: broken CDR ..." for a message that is no VelodyneScan.
VelodyneScanView readVelodyneScanCdr(const std::uint8_t* data, std::size_t size, const std::string& where);
VelodyneScanView readVelodyneScanCdr(ros2::CdrReader& in);

}  // namespace bimloc::sim
