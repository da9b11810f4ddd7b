#include "sim/dataset/localized_mcap_writer.hpp"

#include "sim/dataset/localized_bag_writer.hpp"
#include "sim/dataset/ros2_conversions.hpp"
#include "sim/ros2/mcap_writer.hpp"
#include "sim/ros2/messages.hpp"
#include "sim/ros2/rosbag2_reader.hpp"
#include "sim/ros2/rosbag2_writer.hpp"
#include "sim/ros2/schemas.hpp"

#include <algorithm>
#include <cmath>
#include <map>
#include <stdexcept>

namespace bimloc::sim {
namespace {

// The storey's walls (their axes, as lines at the wall's base and top) and rooms (outline at
// the floor, name at the centroid), in map = the plan's frame.
ros2::MarkerArray planMarkers(const bim::Storey& storey, const std::string& map_frame, std::uint64_t stamp_ns) {
  ros2::MarkerArray a;
  auto marker = [&](const std::string& ns, std::int32_t id, std::int32_t type, ros2::ColorRGBA color) {
    ros2::Marker m;
    m.header.stamp = ros2::Time::fromNanoseconds(static_cast<std::int64_t>(stamp_ns));
    m.header.frame_id = map_frame;
    m.ns = ns, m.id = id, m.type = type;
    m.color = color;
    m.frame_locked = true;
    return m;
  };
  ros2::Marker walls = marker("walls", 0, ros2::Marker::kLineList, {0.2f, 0.2f, 0.2f, 1.0f});
  walls.scale.x = 0.05;  // line width, m
  for (const bim::Wall& w : storey.walls) {
    for (const double z : {0.0, w.height_m}) {
      walls.points.push_back({w.start.x(), w.start.y(), w.start.z() + z});
      walls.points.push_back({w.end.x(), w.end.y(), w.end.z() + z});
    }
    for (const Eigen::Vector3d& p : {w.start, w.end}) {  // the wall's ends, upright
      walls.points.push_back({p.x(), p.y(), p.z()});
      walls.points.push_back({p.x(), p.y(), p.z() + w.height_m});
    }
  }
  a.markers.push_back(std::move(walls));
  ros2::Marker rooms = marker("rooms", 0, ros2::Marker::kLineList, {0.1f, 0.4f, 0.9f, 1.0f});
  rooms.scale.x = 0.03;
  std::int32_t id = 0;
  for (const bim::Room& r : storey.rooms) {
    Eigen::Vector2d centroid = Eigen::Vector2d::Zero();
    for (std::size_t i = 0; i < r.footprint.size(); ++i) {
      const auto& p = r.footprint[i];
      const auto& q = r.footprint[(i + 1) % r.footprint.size()];
      rooms.points.push_back({p.x(), p.y(), r.floor_z + 0.02});
      rooms.points.push_back({q.x(), q.y(), r.floor_z + 0.02});
      centroid += p;
    }
    if (r.footprint.empty()) continue;
    centroid /= static_cast<double>(r.footprint.size());
    ros2::Marker name = marker("room_names", id++, ros2::Marker::kText, {0.1f, 0.4f, 0.9f, 1.0f});
    name.pose.position = {centroid.x(), centroid.y(), r.floor_z + 1.0};
    name.scale.z = 0.4;  // text height, m
    name.text = r.name.empty() ? r.id : r.name;
    a.markers.push_back(std::move(name));
  }
  a.markers.push_back(std::move(rooms));
  return a;
}

}  // namespace

struct LocalizedMcapWriter::Impl {
  // A message of ours, written in time order among the input's (a member type: a field of a
  // type in an anonymous namespace has no linkage to share, -Wsubobject-linkage in unity builds).
  struct Pending {
    std::uint64_t log_time_ns;
    int channel;  // 0: tf, 1: localization
    std::vector<std::uint8_t> data;
  };
  std::string path, input, map_frame, odom_frame, base_frame, tf_topic;
  std::unique_ptr<ros2::McapWriter> out;
  std::vector<Pending> pending;
  bool closed = false;
};

LocalizedMcapWriter::LocalizedMcapWriter(const std::string& path, const std::string& input_bag, std::string map_frame,
                                         std::string odom_frame, std::string base_frame, std::string tf_topic)
    : impl_(std::make_unique<Impl>()) {
  impl_->path = path, impl_->input = input_bag;
  impl_->map_frame = std::move(map_frame), impl_->odom_frame = std::move(odom_frame);
  impl_->base_frame = std::move(base_frame), impl_->tf_topic = std::move(tf_topic);
  impl_->out = std::make_unique<ros2::McapWriter>(path);
}

LocalizedMcapWriter::~LocalizedMcapWriter() = default;

void LocalizedMcapWriter::add(double stamp_s, const Eigen::Isometry3d& T_map_odom, const Eigen::Isometry3d& T_map_base,
                              const Eigen::Matrix3d& covariance_xy_yaw) {
  const auto ns = static_cast<std::uint64_t>(std::llround(stamp_s * 1e9));
  ros2::TFMessage tf;
  tf.transforms.push_back(ros2Transform(ns, impl_->map_frame, impl_->odom_frame, T_map_odom));
  ros2::PoseWithCovarianceStamped pose;
  pose.header = {ros2::Time::fromNanoseconds(static_cast<std::int64_t>(ns)), impl_->map_frame};
  pose.pose.pose = ros2Pose(T_map_base);
  const int index[3] = {0, 1, 5};  // (x, y, yaw) in the row-major 6x6 (x y z roll pitch yaw)
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) pose.pose.covariance[index[i] * 6 + index[j]] = covariance_xy_yaw(i, j);
  impl_->pending.push_back({ns, 0, ros2::serialize(tf)});
  impl_->pending.push_back({ns, 1, ros2::serialize(pose)});
}

void LocalizedMcapWriter::close(const bim::Storey& storey) {
  if (impl_->closed) return;
  impl_->closed = true;
  ros2::McapWriter& out = *impl_->out;
  const ros2::Rosbag2Reader in(impl_->input);
  // The input's topics, with their schemas: ours for the types we know, else the input's own
  // (an MCAP input), else none (schema id 0: the bytes are copied, a viewer cannot decode them).
  std::map<std::string, std::uint16_t> channel;
  auto schemaFor = [&](const std::string& type, const std::string& encoding, const std::string& data) -> std::uint16_t {
    try {
      return out.addSchema(type, "ros2msg", ros2::ros2msgDefinition(type));
    } catch (const std::invalid_argument&) {
      return data.empty() ? 0 : out.addSchema(type, encoding, data);
    }
  };
  for (const auto& t : in.topics()) {
    std::string qos = t.offered_qos_profiles;
    channel[t.name] = out.addChannel(schemaFor(t.type, t.schema_encoding, t.schema_data), t.name,
                                     t.serialization_format.empty() ? "cdr" : t.serialization_format,
                                     {{"offered_qos_profiles", qos}});
  }
  std::uint16_t tf = 0;
  if (const auto it = channel.find(impl_->tf_topic); it != channel.end()) tf = it->second;
  else tf = out.addChannel(schemaFor("tf2_msgs/msg/TFMessage", "", ""), impl_->tf_topic, "cdr",
                           {{"offered_qos_profiles", ros2::qosProfileYaml(false)}});
  const std::uint16_t localization =
      out.addChannel(schemaFor("geometry_msgs/msg/PoseWithCovarianceStamped", "", ""), kLocalizationTopic, "cdr",
                     {{"offered_qos_profiles", ros2::qosProfileYaml(false)}});
  const std::uint16_t plan = out.addChannel(schemaFor("visualization_msgs/msg/MarkerArray", "", ""), kPlanTopic, "cdr",
                                            {{"offered_qos_profiles", ros2::qosProfileYaml(true)}});
  std::stable_sort(impl_->pending.begin(), impl_->pending.end(),
                   [](const Impl::Pending& a, const Impl::Pending& b) { return a.log_time_ns < b.log_time_ns; });
  std::size_t next = 0;
  bool plan_written = false;
  auto writePending = [&](std::uint64_t until) {
    for (; next < impl_->pending.size() && impl_->pending[next].log_time_ns <= until; ++next)
      out.write(impl_->pending[next].channel == 0 ? tf : localization, impl_->pending[next].log_time_ns, impl_->pending[next].data);
  };
  in.forEachMessage({}, [&](const ros2::BagMessage& m) {
    if (!plan_written) {  // once, at the recording's start: latched, a late viewer still gets it
      out.write(plan, m.log_time_ns, ros2::serialize(planMarkers(storey, impl_->map_frame, m.log_time_ns)));
      plan_written = true;
    }
    writePending(m.log_time_ns);
    out.write(channel.at(m.topic->name), m.log_time_ns, m.log_time_ns, m.data, m.size);
  });
  writePending(~std::uint64_t{0});
  out.close();
}

}  // namespace bimloc::sim
