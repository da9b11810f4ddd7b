// The synthetic dataset of `bimloc simulate`: a bag (ROS 1, or ROS 2 in MCAP or SQLite3) as a real robot would record it
// (/velodyne_points, /odom, /tf, /ground_truth), the same data as plain files for people
// without ROS (one PCD per lidar turn, TUM trajectories), and metadata.json describing both.
#pragma once

#include "sim/lidar/lidar_scan.hpp"
#include "sim/odometry/odometry_sample.hpp"

#include <Eigen/Geometry>
#include <nlohmann/json.hpp>

#include <array>
#include <memory>
#include <string>
#include <vector>

namespace bimloc::sim {

// Frames of ROS REP 105 and the topics of the bag.
inline constexpr const char* kMapFrame = "map";
inline constexpr const char* kOdomFrame = "odom";
inline constexpr const char* kBaseFrame = "base_link";
inline constexpr const char* kLidarFrame = "velodyne";
inline constexpr const char* kCloudTopic = "/velodyne_points";
inline constexpr const char* kPacketsTopic = "/velodyne_packets";  // with DatasetInfo::packets_rpm
inline constexpr const char* kOdomTopic = "/odom";
inline constexpr const char* kTfTopic = "/tf";
inline constexpr const char* kGroundTruthTopic = "/ground_truth";

// Every stamp of the dataset (bag, TUM files, clouds/index.csv) is the simulation time plus
// this offset: ROS refuses a zero stamp, and one clock everywhere lets the TUM files be
// compared with anything estimated from the bag.
inline constexpr double kDatasetTimeOffsetS = 1000.0;

struct DatasetInfo {
  // Goes into metadata.json as given (scenario, seed, sensor, odometry preset, world...);
  // the writer adds its own keys (format, frames, topics, files...), which win on a clash.
  nlohmann::json metadata = nlohmann::json::object();
  Eigen::Isometry3d T_base_lidar = Eigen::Isometry3d::Identity();  // mount: base_link -> velodyne
  // Diagonal of /odom's covariances (x, y, z, roll, pitch, yaw), in m^2 and rad^2, or
  // (m/s)^2 and (rad/s)^2 for the twist. The defaults suit a planar wheeled base.
  std::array<double, 6> odometry_pose_variance{1e-3, 1e-3, 1e-6, 1e-6, 1e-6, 1e-3};
  std::array<double, 6> odometry_twist_variance{1e-3, 1e-3, 1e-6, 1e-6, 1e-6, 1e-3};
  // The bag's format: "ros1" (dataset.bag), "mcap" or "sqlite3" (a rosbag2 folder, rosbag2/).
  std::string bag_format = "ros1";
  // An MCAP bag's chunk compression: "zstd" (rosbag2's default), "lz4" or "" (none).
  std::string mcap_compression = "zstd";
  // A ROS 1 bag's chunk compression, as `rosbag record` offers it: "" (none, rosbag's
  // default), "lz4" (--lz4) or "bz2" (--bz2); rosbag's own writer compresses.
  std::string ros1_compression;
  // Where an MCAP chunk is closed (its records' bytes): 4 MiB, or rosbag2's 768 KiB (a chunk
  // then holds about one cloud; a message larger than this makes a chunk of its own).
  std::size_t mcap_chunk_bytes = 4u << 20;
  // When > 0, every turn is also written as the VLP-16's own packets at this rpm: a
  // velodyne_msgs/VelodyneScan on /velodyne_packets in the bag and the UDP stream in
  // velodyne.pcap (`bimloc simulate --packets`).
  double packets_rpm = 0.0;
};

// Each stream (scans, odometry, ground truth) must come with strictly increasing stamps;
// the streams may be interleaved in any way. Throws std::invalid_argument on a bad sample and
// std::runtime_error (naming the path) on an I/O failure.
class DatasetWriter {
 public:
  // Stages in a temporary directory next to out_dir; out_dir must be absent, empty or an
  // earlier dataset, which commit() replaces whole: a dataset never mixes with the files of
  // another (a shorter run would leave the old run's extra PCDs behind).
  DatasetWriter(const std::string& out_dir, DatasetInfo info);
  ~DatasetWriter();  // without commit(): removes the staging directory, out_dir untouched
  DatasetWriter(const DatasetWriter&) = delete;
  DatasetWriter& operator=(const DatasetWriter&) = delete;

  void addScan(const LidarScan& scan);
  void addOdometry(const OdometrySample& odom);
  void addGroundTruth(const GroundTruthSample& truth);

  // Finishes every file and puts the folder in place as out_dir with one rename (or one
  // exchange with an earlier dataset), all or nothing. Returns the file names
  // relative to out_dir (dataset.bag, metadata.json, ..., clouds/000000.pcd, ...).
  std::vector<std::string> commit();

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace bimloc::sim
