// The points of a sensor_msgs/PointCloud2, decoded by field name, offset and datatype as the
// message describes them, never by an assumed struct: the Velodyne driver's x, y, z,
// intensity, ring, time come in whatever order and float widths the driver (or a
// converter: LIO-SAM's, a bag filter) chose. Plain bytes in, no ROS type, so the decoding is
// tested and fuzzed without a bag.
#pragma once

#include <Eigen/Core>

#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

namespace bimloc::sim {

// sensor_msgs/PointField: datatype codes INT8 = 1 ... FLOAT64 = 8 (the message's constants).
struct CloudField {
  std::string name;
  std::uint32_t offset = 0;
  std::uint8_t datatype = 0;
  std::uint32_t count = 1;
};

struct CloudLayout {
  std::vector<CloudField> fields;
  std::uint32_t width = 0, height = 0;  // points = width * height
  std::uint32_t point_step = 0, row_step = 0;
  bool is_bigendian = false;
};

struct CloudPoints {
  std::vector<Eigen::Vector3f> xyz;  // finite points only (an organised cloud pads with NaN)
  // Seconds of each point relative to the header stamp (the driver's `time` field, FLOAT32 or
  // FLOAT64), one per kept point; empty when the cloud has no `time` field.
  std::vector<double> time_s;
};

// Throws std::runtime_error "WHERE: problem" when x, y or z is missing, a field lies outside
// point_step, a datatype is unknown, or the data is shorter than the layout says.
CloudPoints decodeCloud(const CloudLayout& layout, const std::uint8_t* data, std::size_t size, const std::string& where);

}  // namespace bimloc::sim
