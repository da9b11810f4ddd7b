#include "sim/dataset/ros2_bag_writer.hpp"

#include "sim/dataset/ros2_conversions.hpp"
#include "sim/dataset/velodyne_points.hpp"
#include "sim/ros2/messages.hpp"
#include "sim/ros2/rosbag2_writer.hpp"

#include <cmath>
#include <stdexcept>

namespace bimloc::sim {
namespace {

ros2::Header header(std::uint64_t stamp_ns, const std::string& frame) {
  return {ros2::Time::fromNanoseconds(static_cast<std::int64_t>(stamp_ns)), frame};
}

std::array<double, 36> diagonalCovariance(const std::array<double, 6>& variance) {
  std::array<double, 36> covariance{};
  for (std::size_t i = 0; i < 6; ++i) covariance[i * 7] = variance[i];
  return covariance;
}

ros2::Vector3 vector3(const Eigen::Vector3d& v) { return {v.x(), v.y(), v.z()}; }

}  // namespace

Ros2BagWriter::Ros2BagWriter(const std::string& dir, const std::string& storage, const DatasetInfo& info)
    : bag_(std::make_unique<ros2::Rosbag2Writer>(dir, storage, info.mcap_compression, info.mcap_chunk_bytes)), info_(info) {
  const std::pair<const char*, const char*> topics[] = {{kCloudTopic, "sensor_msgs/msg/PointCloud2"},
                                                        {kOdomTopic, "nav_msgs/msg/Odometry"},
                                                        {kTfTopic, "tf2_msgs/msg/TFMessage"},
                                                        {kGroundTruthTopic, "nav_msgs/msg/Odometry"}};
  int* handles[] = {&cloud_, &odom_, &tf_, &truth_};
  for (std::size_t i = 0; i < 4; ++i) {
    *handles[i] = bag_->addTopic(topics[i].first, topics[i].second);
    topics_[topics[i].first].type = topics[i].second;
  }
  if (info.packets_rpm > 0) {
    packets_ = bag_->addTopic(kPacketsTopic, "velodyne_msgs/msg/VelodyneScan");
    topics_[kPacketsTopic].type = "velodyne_msgs/msg/VelodyneScan";
  }
}

Ros2BagWriter::~Ros2BagWriter() = default;

void Ros2BagWriter::writeScan(std::uint64_t stamp_ns, std::uint32_t, const LidarScan& scan) {
  ros2::PointCloud2 cloud;
  cloud.header = header(stamp_ns, kLidarFrame);
  for (const PointFieldLayout& f : velodynePointFields())
    cloud.fields.push_back({f.name, f.offset_bytes, static_cast<std::uint8_t>(f.type == PointFieldType::kFloat32 ? 7 : 4), 1});
  cloud.height = 1;
  cloud.width = static_cast<std::uint32_t>(scan.points.size());
  cloud.point_step = kVelodynePointStepBytes;
  cloud.row_step = cloud.point_step * cloud.width;
  cloud.data = packVelodynePoints(scan.points);
  bool dense = true;
  for (const LidarPoint& p : scan.points) dense = dense && std::isfinite(p.x) && std::isfinite(p.y) && std::isfinite(p.z);
  cloud.is_dense = dense;
  bag_->write(cloud_, stamp_ns, ros2::serialize(cloud));
  ++topics_[kCloudTopic].messages;
}

void Ros2BagWriter::writePackets(std::uint64_t stamp_ns, std::uint32_t, const std::vector<Vlp16StampedPacket>& packets) {
  if (packets_ < 0) throw std::logic_error("Ros2BagWriter: packets written without DatasetInfo::packets_rpm");
  // velodyne_msgs/msg/VelodyneScan: Header, then VelodynePacket[] of {Time stamp; uint8[1206] data}.
  ros2::CdrWriter out;
  ros2::write(out, header(stamp_ns, kLidarFrame));
  out.sequenceLength(packets.size());
  for (const auto& p : packets) {
    ros2::write(out, ros2::Time::fromNanoseconds(std::llround(p.stamp_s * 1e9)));
    out.bytes(p.data.data(), p.data.size());
  }
  bag_->write(packets_, stamp_ns, out.take());
  ++topics_[kPacketsTopic].messages;
}

void Ros2BagWriter::writeOdometry(std::uint64_t stamp_ns, std::uint32_t, const OdometrySample& odom) {
  ros2::Odometry msg;
  msg.header = header(stamp_ns, kOdomFrame);
  msg.child_frame_id = kBaseFrame;
  msg.pose.pose = ros2Pose(odom.T_odom_base);
  msg.pose.covariance = diagonalCovariance(info_.odometry_pose_variance);
  msg.twist.twist.linear = vector3(odom.linear_velocity_base);
  msg.twist.twist.angular = vector3(odom.angular_velocity_base);
  msg.twist.covariance = diagonalCovariance(info_.odometry_twist_variance);
  bag_->write(odom_, stamp_ns, ros2::serialize(msg));
  ++topics_[kOdomTopic].messages;
  // As the ROS 1 bag: the mount rides along with every odometry transform.
  ros2::TFMessage tf;
  tf.transforms.push_back(ros2Transform(stamp_ns, kOdomFrame, kBaseFrame, odom.T_odom_base));
  tf.transforms.push_back(ros2Transform(stamp_ns, kBaseFrame, kLidarFrame, info_.T_base_lidar));
  bag_->write(tf_, stamp_ns, ros2::serialize(tf));
  ++topics_[kTfTopic].messages;
}

void Ros2BagWriter::writeGroundTruth(std::uint64_t stamp_ns, std::uint32_t, const GroundTruthSample& truth) {
  ros2::Odometry msg;
  msg.header = header(stamp_ns, kMapFrame);
  msg.child_frame_id = kBaseFrame;
  msg.pose.pose = ros2Pose(truth.T_map_base);
  bag_->write(truth_, stamp_ns, ros2::serialize(msg));
  ++topics_[kGroundTruthTopic].messages;
}

void Ros2BagWriter::close() { bag_->close(); }

}  // namespace bimloc::sim
