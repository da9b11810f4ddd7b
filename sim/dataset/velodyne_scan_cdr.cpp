#include "sim/dataset/velodyne_scan_cdr.hpp"

#include "sim/lidar/vlp16_packet.hpp"
#include "sim/ros2/messages.hpp"

namespace bimloc::sim {

VelodyneScanView readVelodyneScanCdr(const std::uint8_t* data, std::size_t size, const std::string& where) {
  ros2::CdrReader in(data, size, where);
  return readVelodyneScanCdr(in);
}

VelodyneScanView readVelodyneScanCdr(ros2::CdrReader& in) {
  VelodyneScanView out;
  const ros2::Header header = ros2::readHeader(in);
  out.header_s = header.stamp.seconds();
  out.frame_id = header.frame_id;
  const std::uint32_t count = in.sequenceLength(8 + kVlp16PacketBytes, "packets");
  out.packets.reserve(count);
  for (std::uint32_t i = 0; i < count; ++i) {
    const ros2::Time stamp = ros2::readTime(in);
    out.packets.push_back({stamp.seconds(), in.bytes(kVlp16PacketBytes, "packets.data"), kVlp16PacketBytes});
  }
  return out;
}

}  // namespace bimloc::sim
