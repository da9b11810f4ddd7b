#include "sim/ros2/messages.hpp"

namespace bimloc::sim::ros2 {

Time Time::fromNanoseconds(std::int64_t ns) {
  std::int64_t sec = ns / 1000000000, rest = ns % 1000000000;
  if (rest < 0) rest += 1000000000, --sec;
  return {static_cast<std::int32_t>(sec), static_cast<std::uint32_t>(rest)};
}

Time readTime(CdrReader& in) {
  Time t;
  t.sec = in.i32();
  t.nanosec = in.u32();
  return t;
}

Header readHeader(CdrReader& in) {
  Header h;
  h.stamp = readTime(in);
  h.frame_id = in.string();
  return h;
}

Vector3 readVector3(CdrReader& in) {
  Vector3 v;
  v.x = in.f64(), v.y = in.f64(), v.z = in.f64();
  return v;
}

Quaternion readQuaternion(CdrReader& in) {
  Quaternion q;
  q.x = in.f64(), q.y = in.f64(), q.z = in.f64(), q.w = in.f64();
  return q;
}

Pose readPose(CdrReader& in) {
  Pose p;
  p.position = readVector3(in);
  p.orientation = readQuaternion(in);
  return p;
}

namespace {

void readCovariance(CdrReader& in, std::array<double, 36>& c) {
  for (double& v : c) v = in.f64();
}

void writeCovariance(CdrWriter& out, const std::array<double, 36>& c) {
  for (double v : c) out.f64(v);
}

ColorRGBA readColor(CdrReader& in) {
  ColorRGBA c;
  c.r = in.f32(), c.g = in.f32(), c.b = in.f32(), c.a = in.f32();
  return c;
}

void writeColor(CdrWriter& out, const ColorRGBA& c) {
  out.f32(c.r), out.f32(c.g), out.f32(c.b), out.f32(c.a);
}

}  // namespace

Odometry readOdometry(CdrReader& in) {
  Odometry o;
  o.header = readHeader(in);
  o.child_frame_id = in.string();
  o.pose.pose = readPose(in);
  readCovariance(in, o.pose.covariance);
  o.twist.twist.linear = readVector3(in);
  o.twist.twist.angular = readVector3(in);
  readCovariance(in, o.twist.covariance);
  return o;
}

PoseStamped readPoseStamped(CdrReader& in) {
  PoseStamped p;
  p.header = readHeader(in);
  p.pose = readPose(in);
  return p;
}

PoseWithCovarianceStamped readPoseWithCovarianceStamped(CdrReader& in) {
  PoseWithCovarianceStamped p;
  p.header = readHeader(in);
  p.pose.pose = readPose(in);
  readCovariance(in, p.pose.covariance);
  return p;
}

TransformStamped readTransformStamped(CdrReader& in) {
  TransformStamped t;
  t.header = readHeader(in);
  t.child_frame_id = in.string();
  t.transform.translation = readVector3(in);
  t.transform.rotation = readQuaternion(in);
  return t;
}

TFMessage readTFMessage(CdrReader& in) {
  TFMessage m;
  // A TransformStamped is at least 4 + 4 + 4 (stamp, frame) + 4 (child) + 56 bytes.
  const std::uint32_t n = in.sequenceLength(72, "transforms");
  m.transforms.reserve(n);
  for (std::uint32_t i = 0; i < n; ++i) m.transforms.push_back(readTransformStamped(in));
  return m;
}

PointCloud2 readPointCloud2(CdrReader& in) {
  const std::uint8_t* data = nullptr;
  std::size_t bytes = 0;
  PointCloud2 c = readPointCloud2(in, data, bytes);
  c.data.assign(data, data + bytes);
  return c;
}

PointCloud2 readPointCloud2(CdrReader& in, const std::uint8_t*& data, std::size_t& data_size) {
  PointCloud2 c;
  c.header = readHeader(in);
  c.height = in.u32();
  c.width = in.u32();
  const std::uint32_t fields = in.sequenceLength(13, "fields");  // name (>= 4), offset, datatype, count
  c.fields.reserve(fields);
  for (std::uint32_t i = 0; i < fields; ++i) {
    PointField f;
    f.name = in.string();
    f.offset = in.u32();
    f.datatype = in.u8();
    f.count = in.u32();
    c.fields.push_back(std::move(f));
  }
  c.is_bigendian = in.boolean();
  c.point_step = in.u32();
  c.row_step = in.u32();
  data_size = in.sequenceLength(1, "data");
  data = in.bytes(data_size, "data");
  c.is_dense = in.boolean();
  return c;
}

MarkerArray readMarkerArray(CdrReader& in) {
  MarkerArray a;
  const std::uint32_t n = in.sequenceLength(64, "markers");
  for (std::uint32_t i = 0; i < n; ++i) {
    Marker m;
    m.header = readHeader(in);
    m.ns = in.string();
    m.id = in.i32(), m.type = in.i32(), m.action = in.i32();
    m.pose = readPose(in);
    m.scale = readVector3(in);
    m.color = readColor(in);
    m.lifetime = readTime(in);
    m.frame_locked = in.boolean();
    const std::uint32_t points = in.sequenceLength(24, "points");
    for (std::uint32_t k = 0; k < points; ++k) m.points.push_back(readVector3(in));
    const std::uint32_t colors = in.sequenceLength(16, "colors");
    for (std::uint32_t k = 0; k < colors; ++k) m.colors.push_back(readColor(in));
    m.text = in.string();
    m.mesh_resource = in.string();
    m.mesh_use_embedded_materials = in.boolean();
    a.markers.push_back(std::move(m));
  }
  return a;
}

void write(CdrWriter& out, const Time& v) { out.i32(v.sec), out.u32(v.nanosec); }

void write(CdrWriter& out, const Header& v) {
  write(out, v.stamp);
  out.string(v.frame_id);
}

void write(CdrWriter& out, const Vector3& v) { out.f64(v.x), out.f64(v.y), out.f64(v.z); }

void write(CdrWriter& out, const Quaternion& v) { out.f64(v.x), out.f64(v.y), out.f64(v.z), out.f64(v.w); }

void write(CdrWriter& out, const Pose& v) {
  write(out, v.position);
  write(out, v.orientation);
}

void write(CdrWriter& out, const Odometry& v) {
  write(out, v.header);
  out.string(v.child_frame_id);
  write(out, v.pose.pose);
  writeCovariance(out, v.pose.covariance);
  write(out, v.twist.twist.linear);
  write(out, v.twist.twist.angular);
  writeCovariance(out, v.twist.covariance);
}

void write(CdrWriter& out, const PoseStamped& v) {
  write(out, v.header);
  write(out, v.pose);
}

void write(CdrWriter& out, const PoseWithCovarianceStamped& v) {
  write(out, v.header);
  write(out, v.pose.pose);
  writeCovariance(out, v.pose.covariance);
}

void write(CdrWriter& out, const TransformStamped& v) {
  write(out, v.header);
  out.string(v.child_frame_id);
  write(out, v.transform.translation);
  write(out, v.transform.rotation);
}

void write(CdrWriter& out, const TFMessage& v) {
  out.sequenceLength(v.transforms.size());
  for (const auto& t : v.transforms) write(out, t);
}

void write(CdrWriter& out, const PointCloud2& v) {
  write(out, v.header);
  out.u32(v.height), out.u32(v.width);
  out.sequenceLength(v.fields.size());
  for (const auto& f : v.fields) {
    out.string(f.name);
    out.u32(f.offset);
    out.u8(f.datatype);
    out.u32(f.count);
  }
  out.boolean(v.is_bigendian);
  out.u32(v.point_step), out.u32(v.row_step);
  out.sequenceLength(v.data.size());
  out.bytes(v.data.data(), v.data.size());
  out.boolean(v.is_dense);
}

void write(CdrWriter& out, const MarkerArray& v) {
  out.sequenceLength(v.markers.size());
  for (const Marker& m : v.markers) {
    write(out, m.header);
    out.string(m.ns);
    out.i32(m.id), out.i32(m.type), out.i32(m.action);
    write(out, m.pose);
    write(out, m.scale);
    writeColor(out, m.color);
    write(out, m.lifetime);
    out.boolean(m.frame_locked);
    out.sequenceLength(m.points.size());
    for (const auto& p : m.points) write(out, p);
    out.sequenceLength(m.colors.size());
    for (const auto& c : m.colors) writeColor(out, c);
    out.string(m.text);
    out.string(m.mesh_resource);
    out.boolean(m.mesh_use_embedded_materials);
  }
}

}  // namespace bimloc::sim::ros2
