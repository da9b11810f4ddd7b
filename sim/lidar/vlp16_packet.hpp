// The VLP-16's own data packets, as the VLP-16 User Manual (rev. A, "Data Packet Format" and
// "Precision Azimuth Calculation"; numbers in ../shared/reference.md) specifies them: the
// 1206-byte UDP payload on port 2368 of 12 data blocks of 100 bytes (flag 0xFFEE, azimuth in
// 0.01 deg, 32 channel records of distance in 2 mm units and reflectivity: two firing
// sequences of the 16 lasers), a 4-byte timestamp (microseconds past the hour) and two
// factory bytes (return mode, product id). Plain bytes in, no ROS type, so the decoding is
// tested and fuzzed without a bag.
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

namespace bimloc::sim {

inline constexpr std::size_t kVlp16PacketBytes = 1206;
inline constexpr int kVlp16BlocksPerPacket = 12;
inline constexpr std::size_t kVlp16BlockBytes = 100;
inline constexpr double kVlp16DistanceUnitM = 0.002;
inline constexpr std::uint16_t kVlp16AzimuthUnits = 36000;  // 0.01 deg per unit
inline constexpr std::uint8_t kVlp16ProductId = 0x22;
inline constexpr std::uint16_t kVlp16DataPort = 2368;

enum class Vlp16ReturnMode : std::uint8_t { kStrongest = 0x37, kLast = 0x38, kDual = 0x39 };

// Which return a point is. In dual-return mode the blocks come in pairs with one azimuth: the
// first holds the last return, the second the strongest (the second strongest when the last
// is also the strongest); a laser with one echo repeats it in both blocks.
enum class Vlp16Return : std::uint8_t { kStrongest, kLast, kDualLast, kDualStrongest };

// The firing instant of a channel record relative to the packet's first firing (manual's
// timing table): single return, sequence 2 * block + firing; dual, the pair shares a block's
// firings. `firing` is 0 or 1 (the block's two sequences), `laser` 0..15.
double vlp16FiringOffsetS(int block, int firing, int laser, bool dual);

struct Vlp16DecodeOptions {
  double min_range_m = 0.4;   // the ROS driver's VLP-16 default; points at or below are dropped
  double max_range_m = 130.0;  // above the manual's 100 m: a real unit reports a little farther
  // The manual's per-laser vertical offsets (laser 0 +11.2 mm ... laser 15 -11.2 mm). The
  // drivers' stock calibrations (velodyne_pointcloud's VLP16db.yaml, nebula's VLP16.yaml) set
  // them to 0; the bench's sensor model has them.
  bool vertical_offsets = true;
  // In dual-return mode: keep the last returns, the strongest, or both (a second return equal
  // to the first is dropped, as the drivers do).
  bool keep_last = true, keep_strongest = true;
  // Reproduce tier4/nebula's azimuths (to compare with its clouds): each firing's azimuth
  // rounded to 0.01 deg and, in dual-return mode, the second block of a pair given the next
  // pair's azimuth without interpolation and the packet's last pair's first block no interpolation. The manual's
  // rule otherwise: both blocks of a pair share their azimuth, interpolated to the next pair.
  bool nebula_azimuths = false;
};

struct Vlp16Point {
  float x = 0, y = 0, z = 0;  // metres, sensor frame (x forward, y left, z up)
  float distance_m = 0;
  float azimuth_deg = 0;      // 0..360, clockwise seen from above, 0 along +x
  float elevation_deg = 0;
  std::uint8_t intensity = 0;  // the calibrated reflectivity byte
  std::uint8_t laser = 0;      // laser id = firing order
  std::uint16_t ring = 0;      // 0 = lowest beam (-15 deg)
  std::uint8_t block = 0;      // 0..11 within its packet
  std::uint8_t firing = 0;     // the block's first (0) or second (1) firing sequence
  Vlp16Return kind = Vlp16Return::kStrongest;
  double time_s = 0;           // packet stamp + the firing's offset
};

struct Vlp16PacketHeader {
  Vlp16ReturnMode mode = Vlp16ReturnMode::kStrongest;
  std::uint32_t timestamp_us = 0;  // microseconds past the top of the hour
  // Returns the packet holds that the range filter (Vlp16DecodeOptions) dropped: counted, since
  // every point dropped is said (a 0xFFFF distance, 131 m, is a damaged packet's mark).
  std::size_t below_min_range = 0, beyond_max_range = 0;
};

// The manual's timestamp counts microseconds past the top of the hour: below this.
inline constexpr std::uint32_t kVlp16MicrosecondsPerHour = 3600000000u;

// Appends the packet's points in packet order (block, firing, laser). `stamp_s` is the time of
// the packet's first firing (a driver's packet stamp). Throws std::runtime_error
// "WHERE: problem" for a packet of the wrong size, a block without its 0xFFEE flag, an
// azimuth of 360 deg or more, an unknown return mode or another product than the VLP-16.
Vlp16PacketHeader decodeVlp16Packet(const std::uint8_t* data, std::size_t size, double stamp_s,
                                    const Vlp16DecodeOptions& options, std::vector<Vlp16Point>& out,
                                    const std::string& where);

}  // namespace bimloc::sim
