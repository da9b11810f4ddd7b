// What `bimloc localize` reads of a recorded bag, the same for a ROS 1 bag (rosbag) and a ROS 2
// bag (rosbag2: SQLite3 or MCAP, CDR): the topics, and the messages of the few kinds the
// localization needs, decoded into plain structs. BagInput (bag_reader.hpp) works on this
// interface only, so both formats give the same result by construction.
#pragma once

#include "sim/dataset/cloud_fields.hpp"

#include <cstdint>
#include <functional>
#include <map>
#include <memory>
#include <string>
#include <vector>

namespace bimloc::sim {

// kVelodyneScan: velodyne_msgs VelodyneScan, the VLP-16's raw packets (docs/sensors.md).
enum class BagMessageKind { kPointCloud2, kOdometry, kTFMessage, kPoseStamped, kVelodyneScan };

struct BagPose {  // as geometry_msgs/Pose and Transform: unchecked, as recorded
  double x = 0, y = 0, z = 0, qx = 0, qy = 0, qz = 0, qw = 1;
};

struct BagStampedPose {
  double stamp_s = 0;  // the message's header stamp
  BagPose pose;
};

struct BagTransform {  // one geometry_msgs/TransformStamped of a tf2_msgs/TFMessage
  double stamp_s = 0;
  std::string parent, child;  // header.frame_id, child_frame_id, as recorded
  BagPose pose;
};

struct BagPacket {  // a velodyne_msgs VelodynePacket
  double stamp_s = 0;
  std::vector<std::uint8_t> data;  // 1206 bytes when sound
};

struct BagCloud {  // a sensor_msgs/PointCloud2, or a velodyne_msgs VelodyneScan
  double stamp_s = 0;  // header stamp
  std::string frame_id;
  CloudLayout layout;
  std::vector<std::uint8_t> data;
  // Or the bytes lent by the reader instead of `data` (a ROS 2 message in its decompressed chunk
  // or its SQLite row): valid during the visit only; owned() copies them for a cloud kept longer.
  const std::uint8_t* lent = nullptr;
  std::size_t lent_size = 0;
  std::vector<BagPacket> packets;  // a VelodyneScan's (layout and data then empty)
  const std::uint8_t* bytes() const { return lent ? lent : data.data(); }
  std::size_t byteCount() const { return lent ? lent_size : data.size(); }
  BagCloud owned() const {
    BagCloud c = *this;
    if (lent) c.data.assign(lent, lent + lent_size), c.lent = nullptr, c.lent_size = 0;
    return c;
  }
};

// The cloud's points: the PointCloud2 decoded by its fields (cloud_fields.hpp), or the packets
// decoded as the VLP-16 manual says (velodyne_scan_points.hpp), times relative to the stamp.
CloudPoints decodeBagCloud(const BagCloud& cloud, const std::string& where);

class BagMessages {
 public:
  struct Topic {
    std::string type;
    std::size_t messages = 0;
  };
  virtual ~BagMessages() = default;

  const std::string& path() const { return path_; }
  virtual std::string format() const = 0;  // "ROS 1 bag", "ROS 2 bag (mcap)", ...
  const std::map<std::string, Topic>& topics() const { return topics_; }
  // The type's name in this format: "sensor_msgs/PointCloud2" (ROS 1) or "sensor_msgs/msg/PointCloud2".
  virtual std::string typeName(BagMessageKind kind) const = 0;
  bool hasTopic(const std::string& topic, BagMessageKind kind) const;
  // Things read anyway and said once (a recording cut short).
  virtual std::vector<std::string> warnings() const { return {}; }

  // The messages of one topic in recording order. Each throws std::runtime_error "FILE: ..."
  // for a message that cannot be decoded as its kind.
  virtual void forEachTransform(const std::string& topic, const std::function<void(const BagTransform&)>& visit) const = 0;
  // nav_msgs/Odometry's pose.pose, or geometry_msgs/PoseStamped's pose (by the topic's type).
  virtual void forEachPose(const std::string& topic, const std::function<void(const BagStampedPose&)>& visit) const = 0;
  // When the recorder received each message (seconds), without decoding them.
  virtual std::vector<double> receiveTimes(const std::string& topic) const = 0;
  // `visit` returns false to stop.
  virtual void forEachCloud(const std::string& topic, const std::function<bool(std::shared_ptr<const BagCloud>)>& visit) const = 0;
  // The topic's first cloud, its bytes owned (nullptr when it has none): forEachCloud stopped
  // after one, unless the format knows a cheaper way (a ROS 2 MCAP bag reads no chunk ahead
  // for it, and keeps the chunk for the clouds' read that follows).
  virtual std::shared_ptr<const BagCloud> firstCloud(const std::string& topic) const;

 protected:
  std::string path_;
  std::map<std::string, Topic> topics_;
};

// A ROS 1 bag ("#ROSBAG V2.0"); rosbag stays inside ros1_bag_messages.cpp.
std::unique_ptr<BagMessages> openRos1Bag(const std::string& path);
// A rosbag2 folder, an .mcap file or a .db3 file (sim/ros2).
std::unique_ptr<BagMessages> openRos2Bag(const std::string& path);

}  // namespace bimloc::sim
