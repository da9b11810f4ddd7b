#include "sim/dataset/velodyne_points.hpp"

#include <cstring>
#include <stdexcept>

namespace bimloc::sim {

// Both file formats are little-endian by declaration (is_bigendian false, PCD binary is
// the host's order in practice): copying host floats byte for byte needs a little-endian host.
static_assert(sizeof(float) == 4, "FLOAT32 fields need a 4-byte float");

bool hostIsLittleEndian() {
  const std::uint16_t probe = 1;
  std::uint8_t first = 0;
  std::memcpy(&first, &probe, 1);
  return first == 1;
}

const std::array<PointFieldLayout, 6>& velodynePointFields() {
  static const std::array<PointFieldLayout, 6> fields{{
      {"x", 0, 4, PointFieldType::kFloat32},
      {"y", 4, 4, PointFieldType::kFloat32},
      {"z", 8, 4, PointFieldType::kFloat32},
      {"intensity", 12, 4, PointFieldType::kFloat32},
      {"ring", 16, 2, PointFieldType::kUint16},
      {"time", 18, 4, PointFieldType::kFloat32},
  }};
  return fields;
}

std::vector<std::uint8_t> packVelodynePoints(const std::vector<LidarPoint>& points) {
  static const bool little_endian = hostIsLittleEndian();
  if (!little_endian) throw std::logic_error("packVelodynePoints: big-endian hosts are not supported");
  std::vector<std::uint8_t> data(points.size() * kVelodynePointStepBytes);
  std::uint8_t* out = data.data();
  for (const LidarPoint& p : points) {
    std::memcpy(out + 0, &p.x, 4);
    std::memcpy(out + 4, &p.y, 4);
    std::memcpy(out + 8, &p.z, 4);
    std::memcpy(out + 12, &p.intensity, 4);
    std::memcpy(out + 16, &p.ring, 2);
    std::memcpy(out + 18, &p.time, 4);
    out += kVelodynePointStepBytes;
  }
  return data;
}

}  // namespace bimloc::sim
