#include "sim/lidar/vlp16_packet_encoder.hpp"

#include "sim/lidar/vlp16.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace bimloc::sim {
namespace {

constexpr int kSequencesPerPacket = 2 * kVlp16BlocksPerPacket;

void put16(std::uint8_t* p, std::uint16_t v) {
  p[0] = static_cast<std::uint8_t>(v & 0xFF);
  p[1] = static_cast<std::uint8_t>(v >> 8);
}

}  // namespace

std::vector<Vlp16StampedPacket> encodeVlp16Turn(const LidarScan& scan, double rpm, double stamp_s) {
  const int sequences = static_cast<int>(std::floor(60.0 / rpm / kVlp16CyclePeriod_s));
  const int packets = (sequences + kSequencesPerPacket - 1) / kSequencesPerPacket;
  const double units_per_s = rpm / 60.0 * kVlp16AzimuthUnits;
  std::vector<Vlp16StampedPacket> out(static_cast<std::size_t>(packets));
  for (int n = 0; n < packets; ++n) {
    Vlp16StampedPacket& packet = out[static_cast<std::size_t>(n)];
    const double t_packet = n * kSequencesPerPacket * kVlp16CyclePeriod_s;
    packet.stamp_s = stamp_s + t_packet;
    for (int b = 0; b < kVlp16BlocksPerPacket; ++b) {
      std::uint8_t* block = packet.data.data() + b * kVlp16BlockBytes;
      block[0] = 0xFF, block[1] = 0xEE;
      const double t_block = t_packet + 2 * b * kVlp16CyclePeriod_s;
      const auto azimuth = static_cast<std::uint32_t>(std::llround(units_per_s * t_block)) % kVlp16AzimuthUnits;
      put16(block + 2, static_cast<std::uint16_t>(azimuth));
    }
    // Microseconds past the top of the hour of the packet's first firing.
    const double past_hour = std::fmod(packet.stamp_s, 3600.0);
    const auto us = static_cast<std::uint32_t>(std::floor(past_hour * 1e6));
    for (int i = 0; i < 4; ++i) packet.data[1200 + i] = static_cast<std::uint8_t>(us >> (8 * i));
    packet.data[1204] = static_cast<std::uint8_t>(Vlp16ReturnMode::kStrongest);
    packet.data[1205] = kVlp16ProductId;
  }
  int laser_of_ring[kVlp16Lasers];
  for (int k = 0; k < kVlp16Lasers; ++k) laser_of_ring[vlp16Ring(k)] = k;
  for (const LidarPoint& p : scan.points) {
    if (p.ring >= kVlp16Lasers) throw std::invalid_argument("encodeVlp16Turn: ring " + std::to_string(p.ring) + " of 16");
    const int laser = laser_of_ring[p.ring];
    const double t_sequence = p.time - laser * kVlp16FiringPeriod_s;
    const long sequence = std::lround(t_sequence / kVlp16CyclePeriod_s);
    if (sequence < 0 || sequence >= sequences || std::abs(t_sequence - sequence * kVlp16CyclePeriod_s) > 1e-7)
      throw std::invalid_argument("encodeVlp16Turn: a point at " + std::to_string(p.time) + " s fits no firing of laser " +
                                  std::to_string(laser));
    const Eigen::Vector3d local(p.x, p.y, p.z - vlp16VerticalOffsetM(laser));  // from the laser's own origin
    const long units = std::lround(local.norm() / kVlp16DistanceUnitM);
    if (units <= 0 || units > 0xFFFF) continue;  // not representable: the sensor reports no return
    const auto n = static_cast<std::size_t>(sequence / kSequencesPerPacket);
    const int in_packet = static_cast<int>(sequence % kSequencesPerPacket);
    std::uint8_t* record = out[n].data.data() + (in_packet / 2) * kVlp16BlockBytes + 4 + 3 * (16 * (in_packet % 2) + laser);
    put16(record, static_cast<std::uint16_t>(units));
    record[2] = static_cast<std::uint8_t>(std::clamp(std::lround(p.intensity), 0L, 255L));
  }
  return out;
}

}  // namespace bimloc::sim
