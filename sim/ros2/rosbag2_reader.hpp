// A ROS 2 bag as rosbag2 records it: a folder with metadata.yaml and its storage files
// (SQLite3 `.db3` or `.mcap`, read in the metadata's order), or a single `.mcap` / `.db3` file.
// Gives the topics (name, type, serialization, count) and the messages as raw bytes (CDR for
// every ROS 2 middleware): decode them with messages.hpp or with a CdrReader of your own.
// Every problem throws std::runtime_error naming the file and what is wrong.
#pragma once

#include "sim/ros2/read_plan.hpp"

#include <cstddef>
#include <cstdint>
#include <functional>
#include <memory>
#include <string>
#include <vector>

namespace bimloc::sim::ros2 {

struct BagTopic {
  std::string name;                  // "/velodyne_points"
  std::string type;                  // "sensor_msgs/msg/PointCloud2"
  std::string serialization_format;  // "cdr"
  std::string offered_qos_profiles;  // rosbag2's YAML text, may be empty
  std::string schema_encoding, schema_data;  // MCAP only: "ros2msg" and the type's definition
  std::uint64_t messages = 0;
};

struct BagMessage {
  const BagTopic* topic = nullptr;
  std::uint64_t log_time_ns = 0;       // when the recorder received it
  const std::uint8_t* data = nullptr;  // the serialized message; valid during the visit only
  std::size_t size = 0;
  std::string where;                   // "FILE: /topic message N" for errors
};

// One storage file of a bag (storage_sqlite3.cpp, storage_mcap.cpp).
class Rosbag2Storage {
 public:
  virtual ~Rosbag2Storage() = default;
  virtual const std::vector<BagTopic>& topics() const = 0;
  virtual const std::vector<std::string>& warnings() const = 0;
  // The messages of the topics named (all when empty), in log-time order. `plan`: how far the
  // read will go, which tells MCAP how to decompress its chunks (read_plan.hpp).
  virtual void forEachMessage(const std::vector<std::string>& topics, const std::function<void(const BagMessage&)>& visit,
                              ReadPlan plan = ReadPlan::kAll) const = 0;
  // The log times of a topic's messages, in order, without reading the messages where the
  // storage has an index of them (MCAP's message indexes, SQLite's timestamp column).
  virtual std::vector<std::uint64_t> logTimes(const std::string& topic) const;
};

std::unique_ptr<Rosbag2Storage> openSqlite3Storage(const std::string& path);
std::unique_ptr<Rosbag2Storage> openMcapStorage(const std::string& path);

class Rosbag2Reader {
 public:
  explicit Rosbag2Reader(const std::string& path);
  ~Rosbag2Reader();
  Rosbag2Reader(const Rosbag2Reader&) = delete;
  Rosbag2Reader& operator=(const Rosbag2Reader&) = delete;

  const std::string& path() const { return path_; }
  const std::string& storageIdentifier() const { return storage_; }  // "sqlite3" or "mcap"
  const std::vector<BagTopic>& topics() const { return topics_; }
  const BagTopic* topic(const std::string& name) const;  // nullptr when the bag has none
  // "\n  topic (type, N messages)" for each topic, as the ROS 1 bag reader lists them.
  std::string topicList() const;
  // A recording cut short, a metadata.yaml missing: things read anyway, said once.
  const std::vector<std::string>& warnings() const { return warnings_; }

  // The messages of the topics named (all when empty), file after file, each in log-time order.
  void forEachMessage(const std::vector<std::string>& topics, const std::function<void(const BagMessage&)>& visit,
                      ReadPlan plan = ReadPlan::kAll) const;
  // A topic's log times, file after file (see Rosbag2Storage::logTimes).
  std::vector<std::uint64_t> logTimes(const std::string& topic) const;

 private:
  std::string path_, storage_;
  std::vector<std::unique_ptr<Rosbag2Storage>> files_;
  std::vector<BagTopic> topics_;
  std::vector<std::string> warnings_;
};

// A folder with metadata.yaml, or with .db3/.mcap files; an .mcap file; an SQLite file.
bool isRosbag2(const std::string& path);

}  // namespace bimloc::sim::ros2
