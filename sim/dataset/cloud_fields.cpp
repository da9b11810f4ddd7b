#include "sim/dataset/cloud_fields.hpp"

#include "sim/dataset/velodyne_points.hpp"

#include <cmath>
#include <cstring>
#include <optional>
#include <stdexcept>

namespace bimloc::sim {
namespace {

[[noreturn]] void failCloud(const std::string& where, const std::string& what) { throw std::runtime_error(where + ": " + what); }

std::size_t datatypeBytes(std::uint8_t datatype) {
  switch (datatype) {  // sensor_msgs/PointField constants
    case 1: case 2: return 1;  // INT8, UINT8
    case 3: case 4: return 2;  // INT16, UINT16
    case 5: case 6: case 7: return 4;  // INT32, UINT32, FLOAT32
    case 8: return 8;  // FLOAT64
    default: return 0;
  }
}

// One value of any datatype as a double, byte-swapped when the cloud's order is not the host's.
double readValue(const std::uint8_t* p, std::uint8_t datatype, bool swap) {
  std::uint8_t bytes[8];
  const std::size_t n = datatypeBytes(datatype);
  for (std::size_t i = 0; i < n; ++i) bytes[i] = swap ? p[n - 1 - i] : p[i];
  auto as = [&bytes](auto value) {
    std::memcpy(&value, bytes, sizeof value);
    return static_cast<double>(value);
  };
  switch (datatype) {
    case 1: return as(std::int8_t{});
    case 2: return as(std::uint8_t{});
    case 3: return as(std::int16_t{});
    case 4: return as(std::uint16_t{});
    case 5: return as(std::int32_t{});
    case 6: return as(std::uint32_t{});
    case 7: return as(float{});
    default: return as(double{});
  }
}

}  // namespace

CloudPoints decodeCloud(const CloudLayout& layout, const std::uint8_t* data, std::size_t size, const std::string& where) {
  std::optional<CloudField> axis[3], time;
  for (const CloudField& f : layout.fields) {
    const std::size_t bytes = datatypeBytes(f.datatype);
    const bool wanted = f.name == "x" || f.name == "y" || f.name == "z" || f.name == "time";
    if (!wanted) continue;  // intensity, ring...: not used, any datatype
    if (bytes == 0) failCloud(where, "field '" + f.name + "' has unknown datatype " + std::to_string(f.datatype));
    if (f.count < 1) failCloud(where, "field '" + f.name + "' has count 0");
    if (std::uint64_t{f.offset} + bytes > layout.point_step)
      failCloud(where, "field '" + f.name + "' at offset " + std::to_string(f.offset) + " lies outside point_step " +
                      std::to_string(layout.point_step));
    if (f.name == "time") time = f;
    else axis[f.name[0] - 'x'] = f;
  }
  for (int i = 0; i < 3; ++i)
    if (!axis[i]) failCloud(where, std::string("the cloud has no '") + char('x' + i) + "' field");
  const std::uint64_t width = layout.width, height = layout.height;
  const std::uint64_t row_step = height > 1 ? layout.row_step : width * layout.point_step;
  if (height > 1 && row_step < width * layout.point_step)
    failCloud(where, "row_step " + std::to_string(layout.row_step) + " is shorter than width * point_step");
  const std::uint64_t needed = height == 0 || width == 0 ? 0 : (height - 1) * row_step + width * layout.point_step;
  if (needed > size)
    failCloud(where, "data holds " + std::to_string(size) + " bytes, the layout (" + std::to_string(width) + " x " +
                    std::to_string(height) + " points of " + std::to_string(layout.point_step) + ") needs " +
                    std::to_string(needed));
  const bool swap = layout.is_bigendian == hostIsLittleEndian();
  CloudPoints out;
  out.xyz.reserve(width * height);
  if (time) out.time_s.reserve(width * height);
  for (std::uint64_t r = 0; r < height; ++r) {
    for (std::uint64_t c = 0; c < width; ++c) {
      const std::uint8_t* p = data + r * row_step + c * layout.point_step;
      const Eigen::Vector3d v(readValue(p + axis[0]->offset, axis[0]->datatype, swap),
                              readValue(p + axis[1]->offset, axis[1]->datatype, swap),
                              readValue(p + axis[2]->offset, axis[2]->datatype, swap));
      if (!v.allFinite()) continue;  // no return: organised clouds pad with NaN
      out.xyz.push_back(v.cast<float>());
      if (time) out.time_s.push_back(readValue(p + time->offset, time->datatype, swap));
    }
  }
  return out;
}

}  // namespace bimloc::sim
