// The ROS1 bag of a dataset: the topics a real robot with a VLP-16 and wheel odometry would
// record, plus the simulator's ground truth. rosbag stays inside bag_writer.cpp.
#pragma once

#include "sim/dataset/dataset_writer.hpp"
#include "sim/lidar/vlp16_packet_encoder.hpp"

#include <cstdint>
#include <map>
#include <memory>
#include <string>

namespace bimloc::sim {

class BagWriter {
 public:
  // Opens `path` for writing; throws std::runtime_error naming it.
  BagWriter(const std::string& path, const DatasetInfo& info);
  ~BagWriter();  // closes the bag if still open, swallowing errors (the caller discards it)
  BagWriter(const BagWriter&) = delete;
  BagWriter& operator=(const BagWriter&) = delete;

  // `stamp_ns` is the dataset time (dataset_clock.hpp) of the sample; `seq` its index in
  // its stream, which becomes header.seq.
  void writeScan(std::uint64_t stamp_ns, std::uint32_t seq, const LidarScan& scan);  // /velodyne_points
  // /velodyne_packets: one velodyne_msgs/VelodyneScan a turn, stamped as its first packet
  // (`stamp_ns`); each packet stamped with its first firing (dataset time, packet.stamp_s).
  void writePackets(std::uint64_t stamp_ns, std::uint32_t seq, const std::vector<Vlp16StampedPacket>& packets);
  // /odom, and on /tf both odom -> base_link and the mount base_link -> velodyne.
  void writeOdometry(std::uint64_t stamp_ns, std::uint32_t seq, const OdometrySample& odom);
  void writeGroundTruth(std::uint64_t stamp_ns, std::uint32_t seq, const GroundTruthSample& truth);
  void close();

  // Message count per topic, with the ROS type: {topic: {type, count}}.
  struct TopicCount {
    std::string type;
    std::size_t messages = 0;
  };
  const std::map<std::string, TopicCount>& topics() const { return topics_; }

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
  std::map<std::string, TopicCount> topics_;
};

}  // namespace bimloc::sim
