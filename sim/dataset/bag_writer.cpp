#include "sim/dataset/bag_writer.hpp"

#include "sim/dataset/ros_messages.hpp"
#include "sim/dataset/velodyne_points.hpp"
#include "sim/dataset/velodyne_scan_msg.hpp"

#include <nav_msgs/Odometry.h>
#include <rosbag/bag.h>
#include <sensor_msgs/PointCloud2.h>
#include <tf2_msgs/TFMessage.h>

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace bimloc::sim {

namespace {

std::uint8_t rosDatatype(PointFieldType type) {
  return type == PointFieldType::kFloat32 ? sensor_msgs::PointField::FLOAT32 : sensor_msgs::PointField::UINT16;
}

sensor_msgs::PointCloud2 cloudMessage(std::uint64_t stamp_ns, std::uint32_t seq, const LidarScan& scan) {
  sensor_msgs::PointCloud2 cloud;
  cloud.header = header(rosTime(stamp_ns), seq, kLidarFrame);
  for (const PointFieldLayout& f : velodynePointFields()) {
    sensor_msgs::PointField field;
    field.name = f.name;
    field.offset = f.offset_bytes;
    field.datatype = rosDatatype(f.type);
    field.count = 1;
    cloud.fields.push_back(field);
  }
  cloud.height = 1;  // unorganised, as the driver's PointcloudXYZIRT
  cloud.width = static_cast<std::uint32_t>(scan.points.size());
  cloud.is_bigendian = false;
  cloud.point_step = kVelodynePointStepBytes;
  cloud.row_step = cloud.point_step * cloud.width;
  cloud.data = packVelodynePoints(scan.points);
  bool dense = true;
  for (const LidarPoint& p : scan.points)
    dense = dense && std::isfinite(p.x) && std::isfinite(p.y) && std::isfinite(p.z);
  cloud.is_dense = dense;
  return cloud;
}

// Row-major 6x6 (x, y, z, roll, pitch, yaw) with the given diagonal.
boost::array<double, 36> diagonalCovariance(const std::array<double, 6>& variance) {
  boost::array<double, 36> covariance{};
  for (std::size_t i = 0; i < 6; ++i) covariance[i * 7] = variance[i];
  return covariance;
}

}  // namespace

struct BagWriter::Impl {
  std::string path;
  DatasetInfo info;
  rosbag::Bag bag;

  // rosbag's exceptions name no file: add it.
  template <class Message>
  void write(const std::string& topic, std::uint64_t stamp_ns, const Message& message) {
    ros::Time time;
    time.fromNSec(stamp_ns);
    try {
      bag.write(topic, time, message);
    } catch (const std::exception& e) {
      throw std::runtime_error(path + ": cannot write " + topic + ": " + e.what());
    }
  }
};

BagWriter::BagWriter(const std::string& path, const DatasetInfo& info) : impl_(std::make_unique<Impl>()) {
  impl_->path = path;
  impl_->info = info;
  // Uncompressed by default (rosbag's): the fastest to write and to read, and no tool needs a
  // bz2 / lz4 decoder for it. lz4 and bz2 as `rosbag record --lz4 / --bz2` write them.
  rosbag::CompressionType compression = rosbag::compression::Uncompressed;
  if (info.ros1_compression == "lz4") compression = rosbag::compression::LZ4;
  else if (info.ros1_compression == "bz2") compression = rosbag::compression::BZ2;
  else if (!info.ros1_compression.empty() && info.ros1_compression != "none")
    throw std::invalid_argument(path + ": a ROS 1 bag's chunks are compressed with lz4 or bz2, or not at all, not '" +
                                info.ros1_compression + "'");
  try {
    impl_->bag.open(path, rosbag::bagmode::Write);
    impl_->bag.setCompression(compression);
  } catch (const std::exception& e) {
    throw std::runtime_error(path + ": cannot create the bag: " + e.what());
  }
  topics_[kCloudTopic].type = "sensor_msgs/PointCloud2";
  topics_[kOdomTopic].type = "nav_msgs/Odometry";
  topics_[kTfTopic].type = "tf2_msgs/TFMessage";
  topics_[kGroundTruthTopic].type = "nav_msgs/Odometry";
}

BagWriter::~BagWriter() {
  try {
    impl_->bag.close();
  } catch (...) {  // a bag being thrown away: nothing useful to report from a destructor
  }
}

void BagWriter::writeScan(std::uint64_t stamp_ns, std::uint32_t seq, const LidarScan& scan) {
  impl_->write(kCloudTopic, stamp_ns, cloudMessage(stamp_ns, seq, scan));
  ++topics_[kCloudTopic].messages;
}

void BagWriter::writePackets(std::uint64_t stamp_ns, std::uint32_t seq, const std::vector<Vlp16StampedPacket>& packets) {
  velodyne_msgs::VelodyneScan scan;
  scan.header = header(rosTime(stamp_ns), seq, kLidarFrame);
  scan.packets.resize(packets.size());
  for (std::size_t i = 0; i < packets.size(); ++i) {
    scan.packets[i].stamp = rosTime(static_cast<std::uint64_t>(std::llround(packets[i].stamp_s * 1e9)));
    std::copy(packets[i].data.begin(), packets[i].data.end(), scan.packets[i].data.begin());
  }
  impl_->write(kPacketsTopic, stamp_ns, scan);
  auto& topic = topics_[kPacketsTopic];
  topic.type = "velodyne_msgs/VelodyneScan";
  ++topic.messages;
}

void BagWriter::writeOdometry(std::uint64_t stamp_ns, std::uint32_t seq, const OdometrySample& odom) {
  nav_msgs::Odometry msg;
  msg.header = header(rosTime(stamp_ns), seq, kOdomFrame);
  msg.child_frame_id = kBaseFrame;
  msg.pose.pose = poseMessage(odom.T_odom_base);
  msg.pose.covariance = diagonalCovariance(impl_->info.odometry_pose_variance);
  msg.twist.twist.linear.x = odom.linear_velocity_base.x();
  msg.twist.twist.linear.y = odom.linear_velocity_base.y();
  msg.twist.twist.linear.z = odom.linear_velocity_base.z();
  msg.twist.twist.angular.x = odom.angular_velocity_base.x();
  msg.twist.twist.angular.y = odom.angular_velocity_base.y();
  msg.twist.twist.angular.z = odom.angular_velocity_base.z();
  msg.twist.covariance = diagonalCovariance(impl_->info.odometry_twist_variance);
  impl_->write(kOdomTopic, stamp_ns, msg);
  ++topics_[kOdomTopic].messages;

  // The mount rides along with every odometry transform rather than on /tf_static: a bag
  // has no latching a player must honour, and tf then finds base_link -> velodyne at any
  // time the odometry covers, without extrapolating past its last stamp.
  tf2_msgs::TFMessage tf;
  tf.transforms.push_back(transformMessage(rosTime(stamp_ns), kOdomFrame, kBaseFrame, odom.T_odom_base));
  tf.transforms.push_back(transformMessage(rosTime(stamp_ns), kBaseFrame, kLidarFrame, impl_->info.T_base_lidar));
  impl_->write(kTfTopic, stamp_ns, tf);
  ++topics_[kTfTopic].messages;
}

void BagWriter::writeGroundTruth(std::uint64_t stamp_ns, std::uint32_t seq, const GroundTruthSample& truth) {
  // Exact pose, hence zero covariance; the twist is not simulated for the ground truth.
  nav_msgs::Odometry msg;
  msg.header = header(rosTime(stamp_ns), seq, kMapFrame);
  msg.child_frame_id = kBaseFrame;
  msg.pose.pose = poseMessage(truth.T_map_base);
  impl_->write(kGroundTruthTopic, stamp_ns, msg);
  ++topics_[kGroundTruthTopic].messages;
}

void BagWriter::close() {
  try {
    impl_->bag.close();
  } catch (const std::exception& e) {
    throw std::runtime_error(impl_->path + ": cannot finish the bag: " + e.what());
  }
}

}  // namespace bimloc::sim
