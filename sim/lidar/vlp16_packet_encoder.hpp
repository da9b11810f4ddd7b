// The bench's VLP-16 turns as the sensor's own data packets (vlp16_packet.hpp): what a robot's
// driver would receive from the emulated sensor. Single return (mode 0x37 strongest): the
// model casts one echo per firing.
#pragma once

#include "sim/lidar/lidar_scan.hpp"
#include "sim/lidar/vlp16_packet.hpp"

#include <array>
#include <cstdint>
#include <vector>

namespace bimloc::sim {

struct Vlp16StampedPacket {
  double stamp_s = 0;  // the packet's first firing
  std::array<std::uint8_t, kVlp16PacketBytes> data{};
};

// The packets of one turn cast by Vlp16::scan at `rpm` (points in firing order, `time` since
// the turn's first firing, the laser's vertical offset included): 24 firing sequences a
// packet, block azimuths from the spin (0 at the turn's first firing, clockwise), ranges from
// each laser's own origin in 2 mm units, intensity as the reflectivity byte. The last packet
// of a turn is completed with empty blocks (no returns) whose azimuths continue the spin; a
// real sensor streams on into the next turn. Throws std::invalid_argument for a point that
// fits no firing of the turn. `stamp_s` is the turn's first firing on the recording's clock
// (the packets' stamps and their microseconds past the hour follow from it).
std::vector<Vlp16StampedPacket> encodeVlp16Turn(const LidarScan& scan, double rpm, double stamp_s);

}  // namespace bimloc::sim
