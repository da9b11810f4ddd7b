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

// The per-point time fields of the common lidar drivers, by name (the first present wins):
//   time         Velodyne (velodyne_pointcloud), FLOAT32 seconds relative to the header stamp
//   t            Ouster (ouster-ros), UINT32 nanoseconds relative
//   offset_time  Livox (livox_ros_driver2), UINT32 nanoseconds relative
//   time_stamp   tier4/nebula, UINT32 nanoseconds relative
//   timestamp    Hesai (HesaiLidar_ROS_2.0), RoboSense (rslidar_sdk), Livox: FLOAT64 absolute
//                seconds (nanoseconds when the value is beyond 1e12)
// Units follow the datatype: integers are nanoseconds, floats seconds. A value beyond 1e6 s is
// marked absolute (since the epoch); with the header stamp, makeTimesRelative decides and
// subtracts it.
inline constexpr const char* kCloudTimeFields[] = {"time", "t", "offset_time", "time_stamp", "timestamp"};

struct CloudPoints {
  std::vector<Eigen::Vector3f> xyz;  // finite points only (an organised cloud pads with NaN)
  // Seconds of each point (relative to the header stamp, or since the epoch when
  // time_absolute), one per kept point; empty when the cloud has no time field.
  std::vector<double> time_s;
  std::string time_field;  // the field the times came from ("" without); "packets" for decoded packets
  bool time_absolute = false;
  // The laser of each kept point (`ring`, UINT16 or UINT8, or `channel`); empty without.
  std::vector<std::uint16_t> ring;
};

// Makes the times relative to the header stamp when they are absolute: nearer the stamp than
// zero (a relative time is within a turn of zero, an absolute one within a turn of the stamp,
// on whatever clock the recording has). Sets time_absolute to what was found.
void makeTimesRelative(CloudPoints& points, double header_stamp_s);

// The time field decodeCloud would use, or "" when the layout has none.
std::string cloudTimeField(const CloudLayout& layout);

// Throws std::runtime_error "WHERE: problem" when x, y or z is missing, a field lies outside
// point_step, a datatype is unknown, or the data is shorter than the layout says.
CloudPoints decodeCloud(const CloudLayout& layout, const std::uint8_t* data, std::size_t size, const std::string& where);

}  // namespace bimloc::sim
