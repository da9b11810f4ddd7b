// The dataset's bag as a ROS 2 bag (`bimloc simulate --format mcap|sqlite3`): a rosbag2 folder
// with the ROS 1 bag's topics and messages in their ROS 2 types (no header seq), the same
// stamps and values, so `localize` gives the same result on either.
#pragma once

#include "sim/dataset/bag_writer.hpp"

#include <memory>
#include <string>

namespace bimloc::sim {

namespace ros2 {
class Rosbag2Writer;
}

class Ros2BagWriter final : public DatasetBag {
 public:
  // `storage`: "mcap" (zstd chunks) or "sqlite3". Creates the folder `dir`.
  Ros2BagWriter(const std::string& dir, const std::string& storage, const DatasetInfo& info);
  ~Ros2BagWriter() override;

  void writeScan(std::uint64_t stamp_ns, std::uint32_t seq, const LidarScan& scan) override;
  void writePackets(std::uint64_t stamp_ns, std::uint32_t seq, const std::vector<Vlp16StampedPacket>& packets) override;
  void writeOdometry(std::uint64_t stamp_ns, std::uint32_t seq, const OdometrySample& odom) override;
  void writeGroundTruth(std::uint64_t stamp_ns, std::uint32_t seq, const GroundTruthSample& truth) override;
  void close() override;

 private:
  std::unique_ptr<ros2::Rosbag2Writer> bag_;
  DatasetInfo info_;
  int cloud_ = 0, odom_ = 0, tf_ = 0, truth_ = 0, packets_ = -1;
};

}  // namespace bimloc::sim
