// A velodyne_msgs VelodyneScan (ROS 1 or ROS 2: a header and its raw packets) decoded into one
// cloud with per-point time, as velodyne_pointcloud's transform node makes one cloud of each
// scan message: the points of every packet in order, their times relative to the message's
// header stamp (negative when the driver stamps a scan with its last packet). Plain bytes in.
#pragma once

#include "sim/dataset/cloud_fields.hpp"
#include "sim/lidar/vlp16_packet.hpp"

#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

namespace bimloc::sim {

struct RawPacket {
  double stamp_s = 0;  // the packet's stamp (its first firing)
  const std::uint8_t* data = nullptr;
  std::size_t size = 0;
};

// Throws std::runtime_error "WHERE packet N: problem" for a packet that is no VLP-16 data packet.
CloudPoints decodeVelodyneScan(const std::vector<RawPacket>& packets, double header_stamp_s,
                               const Vlp16DecodeOptions& options, const std::string& where);

}  // namespace bimloc::sim
