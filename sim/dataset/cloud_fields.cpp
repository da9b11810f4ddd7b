#include "sim/dataset/cloud_fields.hpp"

#include "sim/dataset/velodyne_points.hpp"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <optional>
#include <stdexcept>

namespace bimloc::sim {
namespace {

[[noreturn]] void failCloud(const std::string& where, const std::string& what) { throw std::runtime_error(where + ": " + what); }

const char* datatypeName(std::uint8_t datatype) {
  static const char* const names[] = {"INT8", "UINT8", "INT16", "UINT16", "INT32", "UINT32", "FLOAT32", "FLOAT64"};
  return datatype >= 1 && datatype <= 8 ? names[datatype - 1] : "unknown";
}

// One value of any datatype as a double, byte-swapped when the cloud's order is not the host's.
double readValue(const std::uint8_t* p, std::uint8_t datatype, bool swap) {
  std::uint8_t bytes[8];
  const std::size_t n = cloudDatatypeBytes(datatype);
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

// A field decodeCloud reads: x, y, z and the time field it uses (kCloudTimeFields, first present).
bool isRead(const CloudLayout& layout, const std::string& name) {
  return name == "x" || name == "y" || name == "z" || (!name.empty() && name == cloudTimeField(layout));
}

bool isInteger(std::uint8_t datatype) { return datatype >= 1 && datatype <= 6; }

// Where the rows of a checked layout start: row_step apart (a row may carry padding).
struct Geometry {
  std::uint64_t width, height, row_step;
};

struct Axes {
  const CloudField* xyz[3];
  const CloudField* time;
  const CloudField* ring;  // `ring`, else `channel`; informative only (none when unreadable)
};

Axes axesOf(const CloudLayout& layout) {
  Axes a{{nullptr, nullptr, nullptr}, nullptr, nullptr};
  const std::string time_name = cloudTimeField(layout);
  const bool has_ring = std::any_of(layout.fields.begin(), layout.fields.end(), [](const CloudField& f) { return f.name == "ring"; });
  const std::string ring_name = has_ring ? "ring" : "channel";
  for (const CloudField& f : layout.fields) {
    const std::size_t bytes = cloudDatatypeBytes(f.datatype);
    if (!time_name.empty() && f.name == time_name) a.time = &f;
    else if (f.name == "x" || f.name == "y" || f.name == "z") a.xyz[f.name[0] - 'x'] = &f;
    else if (f.name == ring_name && bytes > 0 && std::uint64_t{f.offset} + bytes <= layout.point_step) a.ring = &f;
  }
  return a;
}

Eigen::Vector3d pointAt(const std::uint8_t* p, const Axes& a, bool swap) {
  return {readValue(p + a.xyz[0]->offset, a.xyz[0]->datatype, swap), readValue(p + a.xyz[1]->offset, a.xyz[1]->datatype, swap),
          readValue(p + a.xyz[2]->offset, a.xyz[2]->datatype, swap)};
}

// A point any lidar could have measured: finite, between 1 mm and 10 km. Independent of the
// sensor: it only has to tell numbers from byte-swapped numbers, whose exponents come from
// the low bytes of the mantissa and scatter over 1e-38..1e38.
bool plausible(const Eigen::Vector3d& p) {
  const double r = p.norm();
  return std::isfinite(r) && r > 1e-3 && r < 1e4;
}

// A writer that declares one byte order and writes the other (is_bigendian set on a
// little-endian machine's data) makes every point garbage, yet each is a number. Read a sample
// both ways: refused when the other order is plainly the data's: a quarter of the sample or
// more plausible (an organised cloud may be half NaN padding), and 4x as many as read as
// declared. Garbage in either order (every point at 1e30 m, whose swapped bytes land a few
// percent of the points in range by chance) is left to the range checks.
void checkByteOrder(const CloudLayout& layout, const Axes& a, const Geometry& g, const std::uint8_t* data,
                    const std::string& where) {
  const std::uint64_t n = g.width * g.height;
  if (n == 0) return;
  const bool swap = layout.is_bigendian == hostIsLittleEndian();
  const std::uint64_t samples = std::min<std::uint64_t>(n, 512);
  std::uint64_t as_declared = 0, other = 0;
  for (std::uint64_t s = 0; s < samples; ++s) {
    const std::uint64_t i = s * n / samples;
    const std::uint8_t* p = data + (i / g.width) * g.row_step + (i % g.width) * layout.point_step;
    as_declared += plausible(pointAt(p, a, swap));
    other += plausible(pointAt(p, a, !swap));
  }
  if (other >= 16 && 4 * other >= samples && other > 4 * as_declared)
    failCloud(where, std::string("is_bigendian = ") + (layout.is_bigendian ? "1" : "0") + ", but read so " +
                    std::to_string(as_declared) + " of " + std::to_string(samples) +
                    " sampled points are plausible (finite, 1 mm to 10 km), read in the other byte order " +
                    std::to_string(other) + ": the writer set is_bigendian wrongly (refused rather than read as garbage)");
}

}  // namespace

std::size_t cloudDatatypeBytes(std::uint8_t datatype) {
  switch (datatype) {  // sensor_msgs/PointField constants
    case 1: case 2: return 1;  // INT8, UINT8
    case 3: case 4: return 2;  // INT16, UINT16
    case 5: case 6: case 7: return 4;  // INT32, UINT32, FLOAT32
    case 8: return 8;  // FLOAT64
    default: return 0;
  }
}

CloudLayoutCheck checkCloudLayout(const CloudLayout& layout, std::size_t data_size, const std::string& where) {
  CloudLayoutCheck out;
  const std::string step = std::to_string(layout.point_step);
  // Each field's bytes, [begin, end) within a point; fields of unknown size are not placed.
  struct Span {
    const CloudField* field;
    std::uint64_t begin, end;
  };
  std::vector<Span> spans;
  for (const CloudField& f : layout.fields) {
    const std::size_t bytes = cloudDatatypeBytes(f.datatype);
    const std::string name = "field '" + f.name + "'";
    if (bytes == 0) {
      if (isRead(layout, f.name)) failCloud(where, name + " has unknown datatype " + std::to_string(f.datatype));
      out.warnings.push_back(name + " has unknown datatype " + std::to_string(f.datatype) + " (not read)");
      continue;
    }
    if (f.count < 1) {
      if (isRead(layout, f.name)) failCloud(where, name + " has count 0");
      continue;
    }
    const std::uint64_t end = std::uint64_t{f.offset} + std::uint64_t{bytes} * f.count;
    if (end > layout.point_step)
      failCloud(where, name + " (" + datatypeName(f.datatype) + (f.count > 1 ? " x " + std::to_string(f.count) : "") +
                      " at offset " + std::to_string(f.offset) + ") lies outside point_step " + step);
    spans.push_back({&f, f.offset, end});
  }
  std::sort(spans.begin(), spans.end(), [](const Span& a, const Span& b) { return a.begin < b.begin; });
  for (std::size_t i = 1; i < spans.size(); ++i) {
    const Span &a = spans[i - 1], &b = spans[i];
    if (b.begin < a.end)
      failCloud(where, "fields '" + a.field->name + "' (" + datatypeName(a.field->datatype) + ", bytes " + std::to_string(a.begin) +
                      " to " + std::to_string(a.end - 1) + ") and '" + b.field->name + "' (" + datatypeName(b.field->datatype) +
                      ", bytes " + std::to_string(b.begin) + " to " + std::to_string(b.end - 1) +
                      ") overlap in a point of " + step + " bytes");
  }
  for (const char* axis : {"x", "y", "z"}) {
    const auto n = std::count_if(layout.fields.begin(), layout.fields.end(), [&](const CloudField& f) { return f.name == axis; });
    if (n == 0) failCloud(where, std::string("the cloud has no '") + axis + "' field");
    if (n > 1) failCloud(where, std::string("the cloud has ") + std::to_string(n) + " fields named '" + axis + "'");
    const auto& f = *std::find_if(layout.fields.begin(), layout.fields.end(), [&](const CloudField& g) { return g.name == axis; });
    if (f.datatype != 7 && f.datatype != 8)
      failCloud(where, std::string("field '") + axis + "' is " + datatypeName(f.datatype) + ": coordinates must be FLOAT32 or FLOAT64");
  }
  const std::uint64_t width = layout.width, height = layout.height, row_step = layout.row_step;
  const std::string shape = std::to_string(width) + " x " + std::to_string(height) + " points of " + step + " bytes, row_step " +
                            std::to_string(row_step);
  if (width * height > 0 && layout.point_step == 0) failCloud(where, "point_step is 0 (" + shape + ")");
  if (height > 0 && row_step < width * layout.point_step)
    failCloud(where, "row_step " + std::to_string(row_step) + " is shorter than width * point_step = " +
                    std::to_string(width * layout.point_step) + " (" + shape + ")");
  const std::uint64_t needed = height * row_step;
  if (needed != data_size)
    failCloud(where, "data holds " + std::to_string(data_size) + " bytes, the layout (" + shape + ") describes " +
                    std::to_string(needed) + (needed > data_size ? ": points are missing" : ": the layout does not describe the data"));
  return out;
}

void makeTimesRelative(CloudPoints& points, double header_stamp_s) {
  if (points.time_s.empty()) return;
  const double t = points.time_s.front();
  points.time_absolute = std::abs(t - header_stamp_s) < std::abs(t);
  if (points.time_absolute)
    for (double& v : points.time_s) v -= header_stamp_s;
}

std::string cloudTimeField(const CloudLayout& layout) {
  for (const char* name : kCloudTimeFields)
    for (const CloudField& f : layout.fields)
      if (f.name == name) return name;
  return "";
}

CloudPoints decodeCloud(const CloudLayout& layout, const std::uint8_t* data, std::size_t size, const std::string& where) {
  CloudPoints out;
  out.warnings = checkCloudLayout(layout, size, where).warnings;
  const Axes a = axesOf(layout);
  const Geometry g{layout.width, layout.height, layout.row_step};
  checkByteOrder(layout, a, g, data, where);
  const bool swap = layout.is_bigendian == hostIsLittleEndian();
  out.declared = g.width * g.height;
  out.xyz.reserve(out.declared);
  if (a.time) out.time_s.reserve(out.declared), out.time_field = a.time->name;
  if (a.ring) out.ring.reserve(out.declared);
  // Integer times are nanoseconds; a float `timestamp` in nanoseconds is told by its size.
  const double time_scale = a.time && isInteger(a.time->datatype) ? 1e-9 : 1.0;
  for (std::uint64_t r = 0; r < g.height; ++r) {
    for (std::uint64_t c = 0; c < g.width; ++c) {
      const std::uint8_t* p = data + r * g.row_step + c * layout.point_step;
      const Eigen::Vector3d v = pointAt(p, a, swap);
      if (!v.allFinite()) {  // no return: organised clouds pad with NaN
        ++out.non_finite;
        continue;
      }
      out.xyz.push_back(v.cast<float>());
      if (a.time) out.time_s.push_back(time_scale * readValue(p + a.time->offset, a.time->datatype, swap));
      if (a.ring) out.ring.push_back(static_cast<std::uint16_t>(readValue(p + a.ring->offset, a.ring->datatype, swap)));
    }
  }
  if (!out.time_s.empty()) {
    if (std::abs(out.time_s.front()) > 1e12)
      for (double& t : out.time_s) t *= 1e-9;
    out.time_absolute = std::abs(out.time_s.front()) > 1e6;
  }
  return out;
}

}  // namespace bimloc::sim
