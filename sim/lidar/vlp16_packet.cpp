#include "sim/lidar/vlp16_packet.hpp"

#include "sim/lidar/vlp16.hpp"

#include <cmath>
#include <cstdio>
#include <stdexcept>

namespace bimloc::sim {
namespace {

[[noreturn]] void fail(const std::string& where, const std::string& what) { throw std::runtime_error(where + ": " + what); }

std::uint16_t u16(const std::uint8_t* p) { return static_cast<std::uint16_t>(p[0] | (p[1] << 8)); }

std::string hex(unsigned value) {
  char buffer[8];
  std::snprintf(buffer, sizeof buffer, "0x%02X", value);
  return buffer;
}

// A firing's place within a block: 2.304 us per laser, 55.296 us per sequence, and a block's
// azimuth gap spans its two sequences (110.592 us).
constexpr double kFiringUs = 2.304, kSequenceUs = 55.296, kBlockUs = 2 * kSequenceUs;

// Where each block's firings point: the azimuth of its first firing and the gap to the next
// block's, in 0.01 deg units.
struct BlockAzimuth {
  double base = 0, gap = 0;
};

std::array<BlockAzimuth, kVlp16BlocksPerPacket> blockAzimuths(const std::uint16_t (&azimuth)[kVlp16BlocksPerPacket],
                                                               bool dual, bool nebula) {
  const int step = dual ? 2 : 1;  // the next block that fired later
  std::array<BlockAzimuth, kVlp16BlocksPerPacket> out;
  double last_gap = 0;
  for (int b = 0; b < kVlp16BlocksPerPacket; ++b) {
    const int first = b - (dual ? b % 2 : 0);  // the pair's first block
    const int next = first + step;
    if (next < kVlp16BlocksPerPacket) {
      last_gap = (kVlp16AzimuthUnits + azimuth[next] - azimuth[first]) % kVlp16AzimuthUnits;
      out[b] = {double(azimuth[first]), last_gap};
    } else {
      out[b] = {double(azimuth[first]), last_gap};  // the last block (pair): the previous gap, as the manual says
    }
    if (nebula) {
      // tier4/nebula (vlp16_decoder.cpp): a block's azimuth is the one read for the block
      // `step` ahead of its predecessor (for a pair's second block, the next pair's), and the
      // packet's last block (dual: the last pair's first block) is not interpolated.
      if (b > 0) out[b].base = azimuth[std::min(b - 1 + step, kVlp16BlocksPerPacket - 1)];
      if (b < kVlp16BlocksPerPacket - step)
        out[b].gap = (kVlp16AzimuthUnits + azimuth[b + step] - int(out[b].base)) % kVlp16AzimuthUnits;
      else if (b == kVlp16BlocksPerPacket - step)
        out[b].gap = 0;
      else
        out[b].gap = out[b - 1 - (dual ? 1 : 0)].gap;
    }
  }
  return out;
}

}  // namespace

double vlp16FiringOffsetS(int block, int firing, int laser, bool dual) {
  const int sequence = (dual ? block - block % 2 : 2 * block) + firing;
  return 1e-6 * (sequence * kSequenceUs + laser * kFiringUs);
}

Vlp16PacketHeader decodeVlp16Packet(const std::uint8_t* data, std::size_t size, double stamp_s,
                                    const Vlp16DecodeOptions& options, std::vector<Vlp16Point>& out,
                                    const std::string& where) {
  if (size != kVlp16PacketBytes)
    fail(where, "a VLP-16 data packet has " + std::to_string(kVlp16PacketBytes) + " bytes, this one " + std::to_string(size));
  const std::uint8_t mode = data[1204], product = data[1205];
  if (product != kVlp16ProductId)
    fail(where, "product id " + hex(product) + " is not a VLP-16 (" + hex(kVlp16ProductId) + ")");
  if (mode != 0x37 && mode != 0x38 && mode != 0x39)
    fail(where, "return mode " + hex(mode) + " is none of the manual's 0x37 strongest, 0x38 last, 0x39 dual");
  Vlp16PacketHeader header;
  header.mode = static_cast<Vlp16ReturnMode>(mode);
  header.timestamp_us = std::uint32_t(data[1200]) | std::uint32_t(data[1201]) << 8 | std::uint32_t(data[1202]) << 16 |
                        std::uint32_t(data[1203]) << 24;
  const bool dual = header.mode == Vlp16ReturnMode::kDual;
  std::uint16_t azimuth[kVlp16BlocksPerPacket];
  for (int b = 0; b < kVlp16BlocksPerPacket; ++b) {
    const std::uint8_t* block = data + b * kVlp16BlockBytes;
    if (block[0] != 0xFF || block[1] != 0xEE)
      fail(where, "block " + std::to_string(b) + " does not start with the flag 0xFFEE");
    azimuth[b] = u16(block + 2);
    if (azimuth[b] >= kVlp16AzimuthUnits)
      fail(where, "block " + std::to_string(b) + " has azimuth " + std::to_string(azimuth[b]) + " (0.01 deg), 360 deg or more");
  }
  const auto azimuths = blockAzimuths(azimuth, dual, options.nebula_azimuths);
  double cos_el[kVlp16Lasers], sin_el[kVlp16Lasers];
  for (int l = 0; l < kVlp16Lasers; ++l) {
    cos_el[l] = std::cos(vlp16ElevationDeg(l) * M_PI / 180.0);
    sin_el[l] = std::sin(vlp16ElevationDeg(l) * M_PI / 180.0);
  }
  for (int b = 0; b < kVlp16BlocksPerPacket; ++b) {
    const std::uint8_t* block = data + b * kVlp16BlockBytes;
    Vlp16Return kind = header.mode == Vlp16ReturnMode::kLast ? Vlp16Return::kLast : Vlp16Return::kStrongest;
    if (dual) {
      kind = b % 2 == 0 ? Vlp16Return::kDualLast : Vlp16Return::kDualStrongest;
      if (b % 2 == 0 ? !options.keep_last : !options.keep_strongest) continue;
    }
    for (int f = 0; f < 2; ++f) {
      for (int l = 0; l < kVlp16Lasers; ++l) {
        const std::uint8_t* record = block + 4 + 3 * (16 * f + l);
        const std::uint16_t units = u16(record);
        if (units == 0) continue;  // no return
        // The second return equal to the first: one echo, reported twice.
        if (dual && b % 2 == 1 && options.keep_last && u16(record - kVlp16BlockBytes) == units) continue;
        const double distance = units * kVlp16DistanceUnitM;
        if (!(distance > options.min_range_m)) {
          ++header.below_min_range;
          continue;
        }
        if (!(distance < options.max_range_m)) {
          ++header.beyond_max_range;
          continue;
        }
        const double along = f * kSequenceUs + l * kFiringUs;
        double units_az;
        if (options.nebula_azimuths) {  // single precision and rounding, as nebula computes it
          const float a = float(azimuths[b].base) + float(azimuths[b].gap) * (float(l) * 2.304f + float(f) * 55.296f) / 110.592f;
          units_az = double(static_cast<std::uint16_t>(std::round(a)) % kVlp16AzimuthUnits);
        } else {
          units_az = std::fmod(azimuths[b].base + azimuths[b].gap * along / kBlockUs, double(kVlp16AzimuthUnits));
        }
        const double az = units_az * M_PI / 18000.0;
        const double xy = distance * cos_el[l];
        Vlp16Point p;
        p.x = float(xy * std::cos(az));
        p.y = float(-xy * std::sin(az));  // the azimuth turns clockwise: +y is at 270 deg
        p.z = float(distance * sin_el[l] + (options.vertical_offsets ? vlp16VerticalOffsetM(l) : 0.0));
        p.distance_m = float(distance);
        p.azimuth_deg = float(units_az / 100.0);
        p.elevation_deg = float(vlp16ElevationDeg(l));
        p.intensity = record[2];
        p.laser = static_cast<std::uint8_t>(l);
        p.ring = vlp16Ring(l);
        p.block = static_cast<std::uint8_t>(b);
        p.firing = static_cast<std::uint8_t>(f);
        p.kind = kind;
        p.time_s = stamp_s + vlp16FiringOffsetS(b, f, l, dual);
        out.push_back(p);
      }
    }
  }
  return header;
}

}  // namespace bimloc::sim
