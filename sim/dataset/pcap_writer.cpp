#include "sim/dataset/pcap_writer.hpp"

#include <cmath>
#include <stdexcept>
#include <vector>

namespace bimloc::sim {
namespace {

// pcap's own fields are in the writer's byte order (the magic tells readers which); the
// network headers are big-endian.
void le32(std::vector<std::uint8_t>& b, std::uint32_t v) {
  for (int i = 0; i < 4; ++i) b.push_back(static_cast<std::uint8_t>(v >> (8 * i)));
}
void le16(std::vector<std::uint8_t>& b, std::uint16_t v) { b.push_back(v & 0xFF), b.push_back(v >> 8); }
void be16(std::vector<std::uint8_t>& b, std::uint16_t v) { b.push_back(v >> 8), b.push_back(v & 0xFF); }

// RFC 1071: the ones' complement of the ones' complement sum of 16-bit words.
std::uint16_t internetChecksum(const std::uint8_t* data, std::size_t size, std::uint32_t sum = 0) {
  for (std::size_t i = 0; i + 1 < size; i += 2) sum += std::uint32_t(data[i]) << 8 | data[i + 1];
  if (size % 2) sum += std::uint32_t(data[size - 1]) << 8;
  while (sum >> 16) sum = (sum & 0xFFFF) + (sum >> 16);
  return static_cast<std::uint16_t>(~sum & 0xFFFF);
}

constexpr std::uint8_t kSensorIp[4] = {192, 168, 1, 201};  // the VLP-16's factory address
constexpr std::uint8_t kBroadcastIp[4] = {255, 255, 255, 255};
constexpr std::uint8_t kSensorMac[6] = {0x60, 0x76, 0x88, 0x00, 0x00, 0x01};  // Velodyne's OUI 60:76:88

}  // namespace

PcapWriter::PcapWriter(const std::string& path) : path_(path), out_(path, std::ios::binary | std::ios::trunc) {
  if (!out_) throw std::runtime_error(path + ": cannot create the pcap file");
  std::vector<std::uint8_t> h;
  le32(h, 0xA1B2C3D4);  // microsecond time stamps
  le16(h, 2), le16(h, 4);  // version 2.4
  le32(h, 0), le32(h, 0);  // GMT, accuracy
  le32(h, 65535);          // snapshot length
  le32(h, 1);              // LINKTYPE_ETHERNET
  out_.write(reinterpret_cast<const char*>(h.data()), static_cast<std::streamsize>(h.size()));
}

void PcapWriter::writeUdp(double stamp_s, const std::uint8_t* payload, std::size_t size, std::uint16_t port) {
  if (!(stamp_s >= 0) || size > 65535 - 28) throw std::invalid_argument(path_ + ": a datagram the capture cannot hold");
  std::vector<std::uint8_t> frame;
  frame.reserve(42 + size);
  for (int i = 0; i < 6; ++i) frame.push_back(0xFF);  // to everyone
  frame.insert(frame.end(), kSensorMac, kSensorMac + 6);
  be16(frame, 0x0800);  // IPv4
  const std::size_t ip = frame.size();
  frame.push_back(0x45), frame.push_back(0);  // version 4, 5-word header; no TOS
  be16(frame, static_cast<std::uint16_t>(20 + 8 + size));
  be16(frame, ip_id_++);
  be16(frame, 0x4000);  // don't fragment
  frame.push_back(64), frame.push_back(17);  // TTL, UDP
  be16(frame, 0);       // checksum, below
  frame.insert(frame.end(), kSensorIp, kSensorIp + 4);
  frame.insert(frame.end(), kBroadcastIp, kBroadcastIp + 4);
  const std::uint16_t ip_sum = internetChecksum(frame.data() + ip, 20);
  frame[ip + 10] = static_cast<std::uint8_t>(ip_sum >> 8), frame[ip + 11] = static_cast<std::uint8_t>(ip_sum & 0xFF);
  const std::size_t udp = frame.size();
  const auto udp_length = static_cast<std::uint16_t>(8 + size);
  be16(frame, port), be16(frame, port), be16(frame, udp_length), be16(frame, 0);
  frame.insert(frame.end(), payload, payload + size);
  // The UDP checksum covers a pseudo header: addresses, protocol, length.
  std::uint32_t pseudo = 0;
  for (int i = 0; i < 4; i += 2)
    pseudo += (std::uint32_t(kSensorIp[i]) << 8 | kSensorIp[i + 1]) + (std::uint32_t(kBroadcastIp[i]) << 8 | kBroadcastIp[i + 1]);
  pseudo += 17 + udp_length;
  std::uint16_t udp_sum = internetChecksum(frame.data() + udp, frame.size() - udp, pseudo);
  if (udp_sum == 0) udp_sum = 0xFFFF;  // 0 means "no checksum" in IPv4
  frame[udp + 6] = static_cast<std::uint8_t>(udp_sum >> 8), frame[udp + 7] = static_cast<std::uint8_t>(udp_sum & 0xFF);

  double whole = 0;
  const double fraction = std::modf(stamp_s, &whole);
  auto seconds = static_cast<std::uint32_t>(whole);
  auto micros = static_cast<std::uint32_t>(std::llround(fraction * 1e6));
  if (micros >= 1000000) ++seconds, micros -= 1000000;
  std::vector<std::uint8_t> record;
  le32(record, seconds), le32(record, micros);
  le32(record, static_cast<std::uint32_t>(frame.size())), le32(record, static_cast<std::uint32_t>(frame.size()));
  out_.write(reinterpret_cast<const char*>(record.data()), static_cast<std::streamsize>(record.size()));
  out_.write(reinterpret_cast<const char*>(frame.data()), static_cast<std::streamsize>(frame.size()));
  ++packets_;
}

void PcapWriter::close() {
  out_.close();
  if (!out_) throw std::runtime_error(path_ + ": cannot finish the pcap file");
}

}  // namespace bimloc::sim
