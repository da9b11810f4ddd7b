// The ROS 2 messages bimloc reads and writes, as plain structs with their CDR decoding and
// encoding (cdr.hpp), field by field in the order of their .msg definitions (ROS 2 Humble and
// later). Their ros2msg definitions (the text an MCAP Schema record carries) are in schemas.hpp.
#pragma once

#include "sim/ros2/cdr.hpp"

#include <array>
#include <cstdint>
#include <string>
#include <vector>

namespace bimloc::sim::ros2 {

struct Time {  // builtin_interfaces/msg/Time (and Duration: the same fields)
  std::int32_t sec = 0;
  std::uint32_t nanosec = 0;
  double seconds() const { return sec + 1e-9 * nanosec; }
  static Time fromNanoseconds(std::int64_t ns);
};

struct Header {  // std_msgs/msg/Header: no seq in ROS 2
  Time stamp;
  std::string frame_id;
};

struct Vector3 {
  double x = 0, y = 0, z = 0;
};
struct Quaternion {
  double x = 0, y = 0, z = 0, w = 1;
};
struct Pose {  // geometry_msgs/msg/Pose (position is a Point: x, y, z as a Vector3)
  Vector3 position;
  Quaternion orientation;
};
struct PoseWithCovariance {
  Pose pose;
  std::array<double, 36> covariance{};
};
struct Twist {
  Vector3 linear, angular;
};
struct TwistWithCovariance {
  Twist twist;
  std::array<double, 36> covariance{};
};

struct Odometry {  // nav_msgs/msg/Odometry
  Header header;
  std::string child_frame_id;
  PoseWithCovariance pose;
  TwistWithCovariance twist;
};

struct PoseStamped {  // geometry_msgs/msg/PoseStamped
  Header header;
  Pose pose;
};

struct PoseWithCovarianceStamped {  // geometry_msgs/msg/PoseWithCovarianceStamped
  Header header;
  PoseWithCovariance pose;
};

struct Transform {  // geometry_msgs/msg/Transform
  Vector3 translation;
  Quaternion rotation;
};
struct TransformStamped {
  Header header;
  std::string child_frame_id;
  Transform transform;
};
struct TFMessage {  // tf2_msgs/msg/TFMessage
  std::vector<TransformStamped> transforms;
};

struct PointField {  // sensor_msgs/msg/PointField
  std::string name;
  std::uint32_t offset = 0;
  std::uint8_t datatype = 0;
  std::uint32_t count = 1;
};
struct PointCloud2 {  // sensor_msgs/msg/PointCloud2
  Header header;
  std::uint32_t height = 0, width = 0;
  std::vector<PointField> fields;
  bool is_bigendian = false;
  std::uint32_t point_step = 0, row_step = 0;
  std::vector<std::uint8_t> data;
  bool is_dense = false;
};

struct ColorRGBA {
  float r = 0, g = 0, b = 0, a = 1;
};
struct Marker {  // visualization_msgs/msg/Marker, as ROS 2 Humble defines it
  enum Type : std::int32_t { kCube = 1, kLineList = 5, kTriangleList = 11, kText = 9 };
  Header header;
  std::string ns;
  std::int32_t id = 0, type = 0, action = 0;  // action 0: ADD
  Pose pose;
  Vector3 scale;
  ColorRGBA color;
  Time lifetime;  // 0: forever
  bool frame_locked = false;
  std::vector<Vector3> points;
  std::vector<ColorRGBA> colors;
  std::string text, mesh_resource;
  bool mesh_use_embedded_materials = false;
};
struct MarkerArray {
  std::vector<Marker> markers;
};

// Decoding: each reads its fields at the reader's position (a nested message inside another).
// They throw as CdrReader does, naming the message.
Time readTime(CdrReader& in);
Header readHeader(CdrReader& in);
Vector3 readVector3(CdrReader& in);
Quaternion readQuaternion(CdrReader& in);
Pose readPose(CdrReader& in);
Odometry readOdometry(CdrReader& in);
PoseStamped readPoseStamped(CdrReader& in);
PoseWithCovarianceStamped readPoseWithCovarianceStamped(CdrReader& in);
TransformStamped readTransformStamped(CdrReader& in);
TFMessage readTFMessage(CdrReader& in);
PointCloud2 readPointCloud2(CdrReader& in);
// The same with `data` left empty: its bytes are lent instead (a pointer into the message,
// valid while it lives), for a reader that decodes the points straight from the message.
PointCloud2 readPointCloud2(CdrReader& in, const std::uint8_t*& data, std::size_t& data_size);
MarkerArray readMarkerArray(CdrReader& in);

void write(CdrWriter& out, const Time& v);
void write(CdrWriter& out, const Header& v);
void write(CdrWriter& out, const Vector3& v);
void write(CdrWriter& out, const Quaternion& v);
void write(CdrWriter& out, const Pose& v);
void write(CdrWriter& out, const Odometry& v);
void write(CdrWriter& out, const PoseStamped& v);
void write(CdrWriter& out, const PoseWithCovarianceStamped& v);
void write(CdrWriter& out, const TransformStamped& v);
void write(CdrWriter& out, const TFMessage& v);
void write(CdrWriter& out, const PointCloud2& v);
void write(CdrWriter& out, const MarkerArray& v);

// A whole message: the encapsulation header, then `v`.
template <typename Message>
std::vector<std::uint8_t> serialize(const Message& v) {
  CdrWriter out;
  write(out, v);
  return out.take();
}

}  // namespace bimloc::sim::ros2
