// The points of a sensor_msgs/PointCloud2, decoded by field name, offset and datatype as the
// message describes them, never by an assumed struct: the Velodyne driver's x, y, z,
// intensity, ring, time come in whatever order and float widths the driver (or a
// converter: LIO-SAM's, a bag filter) chose. Plain bytes in, no ROS type, so the decoding is
// tested and fuzzed without a bag, and ROS 1 and ROS 2 messages share it.
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

// Bytes of one value of a sensor_msgs/PointField datatype; 0 for an unknown code.
std::size_t cloudDatatypeBytes(std::uint8_t datatype);

// What a layout says of itself, before any point is read. `warnings`: what is odd but does
// not stop the decoding (a field of unknown datatype that is not read).
struct CloudLayoutCheck {
  std::vector<std::string> warnings;
};

// The one check of a cloud's layout against itself and its data, for ROS 1 and ROS 2 alike.
// Throws std::runtime_error "WHERE: problem" when: x, y or z is missing, given twice, or not
// FLOAT32/FLOAT64; a field read (x, y, z, the time field) has an unknown datatype or count 0; a field
// lies outside point_step or overlaps another; point_step is 0 with points declared;
// row_step is shorter than width * point_step; or the data is not height * row_step bytes
// (shorter: points missing; longer: e.g. height 0 over a full data block, a layout that does
// not describe its data).
CloudLayoutCheck checkCloudLayout(const CloudLayout& layout, std::size_t data_size, const std::string& where);

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
  std::size_t declared = 0;    // width * height
  std::size_t non_finite = 0;  // dropped: NaN or infinite x, y or z
  // Dropped while decoding, by the decoder's range filter (VLP-16 packets), counted in the
  // run's point drops with the others.
  std::size_t below_min_range = 0, beyond_max_range = 0;
  std::vector<std::string> warnings;  // checkCloudLayout's
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

// checkCloudLayout, then the points. The byte order is as declared (is_bigendian: swapped on
// this little-endian host). A cloud whose points are implausible in the declared order but
// plausible in the other (a writer that set is_bigendian wrongly) is refused by name rather
// than read as garbage. The time field is the first of kCloudTimeFields present.
CloudPoints decodeCloud(const CloudLayout& layout, const std::uint8_t* data, std::size_t size, const std::string& where);

}  // namespace bimloc::sim
