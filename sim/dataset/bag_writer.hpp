// The bag of a dataset: the topics a real robot with a VLP-16 and wheel odometry would
// record, plus the simulator's ground truth. DatasetBag is the bag whatever its format;
// BagWriter writes it as a ROS 1 bag (rosbag stays inside bag_writer.cpp), Ros2BagWriter
// (ros2_bag_writer.hpp) as a rosbag2 folder.
#pragma once

#include "sim/dataset/dataset_writer.hpp"
#include "sim/lidar/vlp16_packet_encoder.hpp"

#include <cstdint>
#include <map>
#include <memory>
#include <string>

namespace bimloc::sim {

class DatasetBag {
 public:
  virtual ~DatasetBag() = default;
  // `stamp_ns` is the dataset time (dataset_clock.hpp) of the sample; `seq` its index in
  // its stream, which becomes header.seq (ROS 1; a ROS 2 header has none).
  virtual void writeScan(std::uint64_t stamp_ns, std::uint32_t seq, const LidarScan& scan) = 0;  // /velodyne_points
  // /velodyne_packets: one velodyne_msgs VelodyneScan a turn, stamped as its first packet
  // (`stamp_ns`); each packet stamped with its first firing (dataset time, packet.stamp_s).
  virtual void writePackets(std::uint64_t stamp_ns, std::uint32_t seq, const std::vector<Vlp16StampedPacket>& packets) = 0;
  // /odom, and on /tf both odom -> base_link and the mount base_link -> velodyne.
  virtual void writeOdometry(std::uint64_t stamp_ns, std::uint32_t seq, const OdometrySample& odom) = 0;
  virtual void writeGroundTruth(std::uint64_t stamp_ns, std::uint32_t seq, const GroundTruthSample& truth) = 0;
  virtual void close() = 0;

  // Message count per topic, with the ROS type: {topic: {type, count}}.
  struct TopicCount {
    std::string type;
    std::size_t messages = 0;
  };
  const std::map<std::string, TopicCount>& topics() const { return topics_; }

 protected:
  std::map<std::string, TopicCount> topics_;
};

class BagWriter final : public DatasetBag {
 public:
  // Opens `path` for writing; throws std::runtime_error naming it.
  BagWriter(const std::string& path, const DatasetInfo& info);
  ~BagWriter() override;  // closes the bag if still open, swallowing errors (the caller discards it)
  BagWriter(const BagWriter&) = delete;
  BagWriter& operator=(const BagWriter&) = delete;

  void writeScan(std::uint64_t stamp_ns, std::uint32_t seq, const LidarScan& scan) override;
  void writePackets(std::uint64_t stamp_ns, std::uint32_t seq, const std::vector<Vlp16StampedPacket>& packets) override;
  void writeOdometry(std::uint64_t stamp_ns, std::uint32_t seq, const OdometrySample& odom) override;
  void writeGroundTruth(std::uint64_t stamp_ns, std::uint32_t seq, const GroundTruthSample& truth) override;
  void close() override;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace bimloc::sim
