// A recorded bag, ROS 1 or ROS 2 (rosbag2: SQLite3 or MCAP; bag_messages.hpp reads both), as
// `bimloc localize` uses it: the lidar turns (sensor_msgs/PointCloud2),
// the odometry (nav_msgs/Odometry, or the /tf transform odom -> base_link), the lidar mount
// (base_link -> the cloud's frame on /tf_static or /tf, or given), and the ground truth when
// the bag has it (as `bimloc simulate` writes it; nav_msgs/Odometry or geometry_msgs/PoseStamped).
#pragma once

#include "sim/dataset/dataset_reader.hpp"
#include "sim/dataset/recording_checks.hpp"

#include <Eigen/Geometry>
#include <functional>
#include <memory>
#include <optional>
#include <string>
#include <vector>

namespace bimloc::sim {

struct BagInputOptions {
  // sensor_msgs/PointCloud2 (the velodyne_pointcloud driver's), or velodyne_msgs/VelodyneScan
  // (the VLP-16's raw packets, decoded here: one turn a message)
  std::string cloud_topic = "/velodyne_points";
  // nav_msgs/Odometry; when the bag does not have it and odom_topic_given is false, the /tf
  // transform odom_frame -> base_frame is the odometry.
  std::string odom_topic = "/odom";
  bool odom_topic_given = false;
  std::string odom_frame = "odom";  // REP 105
  std::string base_frame = "base_link";
  std::string truth_topic = "/ground_truth";  // nav_msgs/Odometry in map; optional
  std::string tf_topic = "/tf", tf_static_topic = "/tf_static";
  std::optional<Eigen::Isometry3d> mount;  // base_link -> lidar; else from the bag's tf
  bool deskew = true;                      // with the clouds' per-point `time` field
  SensorRange range;                       // points outside it are dropped, and counted
};

// A lidar turn of the bag, its points decoded (and de-skewed) only when asked.
struct BagTurn {
  double stamp_s = 0;      // the turn's middle: the reference of the de-skew
  std::size_t index = 0;   // among the cloud topic's messages
  std::function<std::vector<Eigen::Vector3f>()> points;  // in the lidar frame at stamp_s; the usable ones
  PointDrops drops;                   // what the decoding and the range check dropped
  std::vector<std::string> warnings;  // the cloud's layout's (checkCloudLayout)
};

class BagInput {
 public:
  // Reads and checks everything but the clouds' points. Throws std::runtime_error
  // "BAG: problem": not a bag, damaged, a topic missing (listing the bag's topics and types),
  // no odometry (or no sample of it a pose), no mount. Odometry and truth samples that are no
  // pose are dropped and counted (odometryDrops, groundTruthDrops).
  BagInput(const std::string& path, const BagInputOptions& options);
  ~BagInput();
  BagInput(const BagInput&) = delete;
  BagInput& operator=(const BagInput&) = delete;

  const std::string& path() const { return path_; }
  const Eigen::Isometry3d& T_base_lidar() const { return T_base_lidar_; }
  const std::string& lidarFrame() const { return lidar_frame_; }
  const std::string& odometrySource() const { return odometry_source_; }  // "/odom (nav_msgs/Odometry)", ...
  const std::string& mountSource() const { return mount_source_; }
  double turnPeriod() const { return turn_period_s_; }
  std::size_t turns() const { return turns_; }
  double firstTurnStamp() const { return first_turn_s_; }  // BagTurn::stamp_s of the first turn
  bool timed() const { return timed_; }  // the clouds carry a per-point time (cloud_fields.hpp)
  const std::string& timeField() const { return time_field_; }  // its name; "packets" for decoded packets
  bool packets() const { return packets_; }  // the cloud topic holds velodyne_msgs/VelodyneScan
  const std::vector<StampedPose>& odometry() const { return odometry_; }        // odom <- base_link
  const std::vector<StampedPose>& groundTruth() const { return ground_truth_; }  // map <- base_link; may be empty
  // Samples that were no pose (not finite, a zero or non-unit quaternion): dropped, counted.
  const PoseSampleDrops& odometryDrops() const { return odometry_drops_; }
  const PoseSampleDrops& groundTruthDrops() const { return truth_drops_; }
  // "topic (type, N messages)" for each topic of the bag, one a line.
  std::string topicList() const;
  // Things read anyway, said once: a ROS 2 recording cut short, a folder without metadata.yaml,
  // a compressed ROS 1 chunk whose size field is wrong. Some are found only as the messages are
  // read: ask again after forEachTurn.
  std::vector<std::string> warnings() const;

  // Calls `visit` for each turn in order, its points decoded and checked (a turn with no usable
  // point is still visited: the caller skips it). Throws as the constructor for a damaged
  // cloud or a layout that contradicts itself (checkCloudLayout).
  void forEachTurn(const std::function<void(const BagTurn&)>& visit) const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
  std::string path_;
  BagInputOptions options_;
  Eigen::Isometry3d T_base_lidar_ = Eigen::Isometry3d::Identity();
  std::string lidar_frame_, odometry_source_, mount_source_;
  double turn_period_s_ = 0.1, first_offset_s_ = 0.0, first_turn_s_ = 0.0;
  std::size_t turns_ = 0;
  bool timed_ = false, packets_ = false;
  std::string time_field_;
  std::vector<StampedPose> odometry_, ground_truth_;
  PoseSampleDrops odometry_drops_, truth_drops_;
};

// True when the file starts with the ROS1 bag magic "#ROSBAG V2.0".
bool isRosBag(const std::string& path);

}  // namespace bimloc::sim
