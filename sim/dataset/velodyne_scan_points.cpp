#include "sim/dataset/velodyne_scan_points.hpp"

namespace bimloc::sim {

CloudPoints decodeVelodyneScan(const std::vector<RawPacket>& packets, double header_stamp_s,
                               const Vlp16DecodeOptions& options, const std::string& where) {
  std::vector<Vlp16Point> points;
  points.reserve(packets.size() * 384);
  CloudPoints out;
  bool stamp_past_hour = false;
  for (std::size_t i = 0; i < packets.size(); ++i) {
    const Vlp16PacketHeader h = decodeVlp16Packet(packets[i].data, packets[i].size, packets[i].stamp_s, options, points,
                                                  where + " packet " + std::to_string(i));
    out.below_min_range += h.below_min_range;
    out.beyond_max_range += h.beyond_max_range;
    stamp_past_hour = stamp_past_hour || h.timestamp_us >= kVlp16MicrosecondsPerHour;
  }
  // The points' times come from the messages' stamps (as the ROS drivers' do); the packet's own
  // timestamp is not used, but one past the hour is no VLP-16's: said, not silently passed.
  if (stamp_past_hour)
    out.warnings.push_back("VLP-16 packets with a timestamp past the hour (the manual's microseconds past the hour): "
                           "not used, the points' times come from the messages' stamps");
  out.xyz.reserve(points.size());
  out.time_s.reserve(points.size());
  out.ring.reserve(points.size());
  for (const Vlp16Point& p : points) {
    out.xyz.emplace_back(p.x, p.y, p.z);
    out.time_s.push_back(p.time_s - header_stamp_s);
    out.ring.push_back(p.ring);
  }
  out.time_field = "packets";
  return out;
}

}  // namespace bimloc::sim
