// A libpcap capture file of the VLP-16's UDP stream, as `tcpdump -w` or Wireshark would have
// recorded it on the sensor's network: the classic pcap global header (microsecond stamps,
// Ethernet link type), then per packet an Ethernet II frame with an IPv4 header and a UDP
// header around the 1206-byte payload, from the sensor's factory address 192.168.1.201 to
// the broadcast address, port 2368 to 2368. Drivers replay such files (velodyne_driver's
// pcap option, nebula's, VeloView). Written by us: no libpcap needed.
#pragma once

#include <cstddef>
#include <cstdint>
#include <fstream>
#include <string>

namespace bimloc::sim {

class PcapWriter {
 public:
  // Creates `path`; throws std::runtime_error naming it.
  explicit PcapWriter(const std::string& path);
  // One UDP datagram captured at `stamp_s` (seconds since the epoch, >= 0).
  void writeUdp(double stamp_s, const std::uint8_t* payload, std::size_t size, std::uint16_t port);
  // Flushes and closes; throws std::runtime_error naming the file on a write error.
  void close();
  std::size_t packets() const { return packets_; }

 private:
  std::string path_;
  std::ofstream out_;
  std::size_t packets_ = 0;
  std::uint16_t ip_id_ = 0;
};

}  // namespace bimloc::sim
