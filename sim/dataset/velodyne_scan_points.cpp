#include "sim/dataset/velodyne_scan_points.hpp"

namespace bimloc::sim {

CloudPoints decodeVelodyneScan(const std::vector<RawPacket>& packets, double header_stamp_s,
                               const Vlp16DecodeOptions& options, const std::string& where) {
  std::vector<Vlp16Point> points;
  points.reserve(packets.size() * 384);
  for (std::size_t i = 0; i < packets.size(); ++i)
    decodeVlp16Packet(packets[i].data, packets[i].size, packets[i].stamp_s, options, points,
                      where + " packet " + std::to_string(i));
  CloudPoints out;
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
