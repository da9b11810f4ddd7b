// ros2_dump BAG: every message of a ROS 2 bag (rosbag2 folder, .mcap, .db3) as bimloc's own
// reader and CDR decoding see it, one JSON document on stdout: the side of the npm oracle
// (check_mcap.mjs) that is ours. Byte arrays are given as their CRC-32 and length.
#include "sim/ros2/crc32.hpp"
#include "sim/ros2/messages.hpp"
#include "sim/ros2/rosbag2_reader.hpp"

#include <nlohmann/json.hpp>

#include <iostream>

using namespace bimloc::sim::ros2;
using nlohmann::json;

namespace {

json time(const Time& t) { return {{"sec", t.sec}, {"nanosec", t.nanosec}}; }
json header(const Header& h) { return {{"stamp", time(h.stamp)}, {"frame_id", h.frame_id}}; }
json vec(const Vector3& v) { return {{"x", v.x}, {"y", v.y}, {"z", v.z}}; }
json quat(const Quaternion& q) { return {{"x", q.x}, {"y", q.y}, {"z", q.z}, {"w", q.w}}; }
json pose(const Pose& p) { return {{"position", vec(p.position)}, {"orientation", quat(p.orientation)}}; }
json array36(const std::array<double, 36>& a) { return json(std::vector<double>(a.begin(), a.end())); }
json bytes(const std::vector<std::uint8_t>& b) {
  return {{"$bytes_crc32", crc32Update(0, b.data(), b.size())}, {"$bytes_length", b.size()}};
}
json color(const ColorRGBA& c) { return {{"r", c.r}, {"g", c.g}, {"b", c.b}, {"a", c.a}}; }

json decode(const std::string& type, CdrReader& in) {
  if (type == "sensor_msgs/msg/PointCloud2") {
    const PointCloud2 c = readPointCloud2(in);
    json fields = json::array();
    for (const auto& f : c.fields) fields.push_back({{"name", f.name}, {"offset", f.offset}, {"datatype", f.datatype}, {"count", f.count}});
    return {{"header", header(c.header)}, {"height", c.height}, {"width", c.width}, {"fields", fields},
            {"is_bigendian", c.is_bigendian}, {"point_step", c.point_step}, {"row_step", c.row_step},
            {"data", bytes(c.data)}, {"is_dense", c.is_dense}};
  }
  if (type == "nav_msgs/msg/Odometry") {
    const Odometry o = readOdometry(in);
    return {{"header", header(o.header)}, {"child_frame_id", o.child_frame_id},
            {"pose", {{"pose", pose(o.pose.pose)}, {"covariance", array36(o.pose.covariance)}}},
            {"twist", {{"twist", {{"linear", vec(o.twist.twist.linear)}, {"angular", vec(o.twist.twist.angular)}}},
                       {"covariance", array36(o.twist.covariance)}}}};
  }
  if (type == "tf2_msgs/msg/TFMessage") {
    json transforms = json::array();
    for (const auto& t : readTFMessage(in).transforms)
      transforms.push_back({{"header", header(t.header)}, {"child_frame_id", t.child_frame_id},
                            {"transform", {{"translation", vec(t.transform.translation)}, {"rotation", quat(t.transform.rotation)}}}});
    return {{"transforms", transforms}};
  }
  if (type == "geometry_msgs/msg/PoseStamped") {
    const PoseStamped p = readPoseStamped(in);
    return {{"header", header(p.header)}, {"pose", pose(p.pose)}};
  }
  if (type == "geometry_msgs/msg/PoseWithCovarianceStamped") {
    const PoseWithCovarianceStamped p = readPoseWithCovarianceStamped(in);
    return {{"header", header(p.header)}, {"pose", {{"pose", pose(p.pose.pose)}, {"covariance", array36(p.pose.covariance)}}}};
  }
  if (type == "visualization_msgs/msg/MarkerArray") {
    json markers = json::array();
    for (const Marker& m : readMarkerArray(in).markers) {
      json points = json::array(), colors = json::array();
      for (const auto& p : m.points) points.push_back(vec(p));
      for (const auto& c : m.colors) colors.push_back(color(c));
      markers.push_back({{"header", header(m.header)}, {"ns", m.ns}, {"id", m.id}, {"type", m.type}, {"action", m.action},
                         {"pose", pose(m.pose)}, {"scale", vec(m.scale)}, {"color", color(m.color)},
                         {"lifetime", time(m.lifetime)}, {"frame_locked", m.frame_locked}, {"points", points},
                         {"colors", colors}, {"text", m.text}, {"mesh_resource", m.mesh_resource},
                         {"mesh_use_embedded_materials", m.mesh_use_embedded_materials}});
    }
    return {{"markers", markers}};
  }
  return nullptr;  // a type we do not decode: only its envelope is compared
}

}  // namespace

int main(int argc, char** argv) {
  if (argc != 2) {
    std::cerr << "usage: ros2_dump BAG\n";
    return 2;
  }
  try {
    const Rosbag2Reader bag(argv[1]);
    json out = {{"storage", bag.storageIdentifier()}, {"warnings", bag.warnings()}, {"topics", json::array()}, {"messages", json::array()}};
    for (const auto& t : bag.topics())
      out["topics"].push_back({{"name", t.name}, {"type", t.type}, {"serialization_format", t.serialization_format},
                               {"messages", t.messages}, {"offered_qos_profiles", t.offered_qos_profiles}});
    bag.forEachMessage({}, [&](const BagMessage& m) {
      CdrReader in(m.data, m.size, m.where);
      out["messages"].push_back({{"topic", m.topic->name}, {"log_time", std::to_string(m.log_time_ns)},
                                 {"message", decode(m.topic->type, in)}});
    });
    std::cout << out.dump() << "\n";
  } catch (const std::exception& e) {
    std::cerr << "ros2_dump: " << e.what() << "\n";
    return 1;
  }
  return 0;
}
