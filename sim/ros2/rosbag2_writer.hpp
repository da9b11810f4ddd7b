// Writes a rosbag2 folder as `ros2 bag record` leaves it: metadata.yaml (version 5) and one
// storage file, rosbag2_0.mcap (zstd chunks, summary, indexes; ros2msg schemas) or
// rosbag2_0.db3 (SQLite3, the tables of rosbag2_storage_default_plugins).
#pragma once

#include <cstddef>
#include <cstdint>
#include <memory>
#include <string>
#include <vector>

namespace bimloc::sim::ros2 {

// rosbag2's offered_qos_profiles YAML for a topic: reliable, volatile, or transient_local
// ("latched": a late subscriber still gets the last message, as /tf_static).
std::string qosProfileYaml(bool transient_local);

class Rosbag2Writer {
 public:
  // `storage`: "mcap" or "sqlite3". Creates `dir` (which must not exist or be empty) and the
  // storage file. Throws std::runtime_error naming the path. MCAP: the chunks' compression, and
  // the size at which a chunk is closed (McapWriterOptions; rosbag2 closes them at 768 KiB).
  Rosbag2Writer(const std::string& dir, const std::string& storage, const std::string& mcap_compression = "zstd",
                std::size_t mcap_chunk_bytes = 4u << 20);
  ~Rosbag2Writer();
  Rosbag2Writer(const Rosbag2Writer&) = delete;
  Rosbag2Writer& operator=(const Rosbag2Writer&) = delete;

  // Declares a topic of a type schemas.hpp knows; returns its handle for write().
  int addTopic(const std::string& name, const std::string& type, bool transient_local = false);
  void write(int topic, std::uint64_t log_time_ns, const std::vector<std::uint8_t>& cdr);
  // Finishes the storage file and writes metadata.yaml.
  void close();

  const std::string& storageFile() const { return file_; }  // "rosbag2_0.mcap"

  struct Storage;  // the file format behind (rosbag2_writer.cpp, sqlite3_writer.cpp)

 private:
  struct Topic {
    std::string name, type, qos;
    std::uint64_t messages = 0;
    int storage_id = 0;
  };
  std::string dir_, storage_, file_;
  std::unique_ptr<Storage> out_;
  std::vector<Topic> topics_;
  std::uint64_t first_ns_ = 0, last_ns_ = 0, messages_ = 0;
  bool closed_ = false;
};

struct Rosbag2Writer::Storage {
  virtual ~Storage() = default;
  virtual int addTopic(const std::string& name, const std::string& type, const std::string& qos) = 0;
  virtual void write(int topic, std::uint64_t log_time_ns, const std::vector<std::uint8_t>& cdr) = 0;
  virtual void close() = 0;
};

std::unique_ptr<Rosbag2Writer::Storage> createSqlite3Storage(const std::string& path);

}  // namespace bimloc::sim::ros2
