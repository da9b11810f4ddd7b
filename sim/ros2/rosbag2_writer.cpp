#include "sim/ros2/rosbag2_writer.hpp"

#include "sim/ros2/mcap_writer.hpp"
#include "sim/ros2/schemas.hpp"

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <stdexcept>

namespace bimloc::sim::ros2 {
namespace {

namespace fs = std::filesystem;

class McapStorageWriter final : public Rosbag2Writer::Storage {
 public:
  McapStorageWriter(const std::string& path, const std::string& compression, std::size_t chunk_bytes) : writer_(path, [&] {
    McapWriterOptions o;
    o.compression = compression;
    o.chunk_bytes = chunk_bytes;
    return o;
  }()) {}
  int addTopic(const std::string& name, const std::string& type, const std::string& qos) override {
    const std::uint16_t schema = writer_.addSchema(type, "ros2msg", ros2msgDefinition(type));
    return writer_.addChannel(schema, name, "cdr", {{"offered_qos_profiles", qos}});
  }
  void write(int topic, std::uint64_t log_time_ns, const std::vector<std::uint8_t>& cdr) override {
    writer_.write(static_cast<std::uint16_t>(topic), log_time_ns, cdr);
  }
  void close() override { writer_.close(); }

 private:
  McapWriter writer_;
};

// A YAML double-quoted scalar.
std::string quoted(const std::string& s) {
  std::string out = "\"";
  for (char c : s) {
    if (c == '"' || c == '\\') out += '\\', out += c;
    else if (c == '\n') out += "\\n";
    else out += c;
  }
  return out + "\"";
}

}  // namespace

std::string qosProfileYaml(bool transient_local) {
  // rosbag2's keys (Humble): history 3 (unknown), reliability 1 (reliable), durability 1
  // (transient_local) or 2 (volatile), liveliness 1 (automatic), durations "infinite".
  const std::string infinite = "\n    sec: 2147483647\n    nsec: 4294967295";
  return "- history: 3\n  depth: 0\n  reliability: 1\n  durability: " + std::string(transient_local ? "1" : "2") +
         "\n  deadline:" + infinite + "\n  lifespan:" + infinite + "\n  liveliness: 1\n  liveliness_lease_duration:" + infinite +
         "\n  avoid_ros_namespace_conventions: false";
}

Rosbag2Writer::Rosbag2Writer(const std::string& dir, const std::string& storage, const std::string& mcap_compression,
                             std::size_t mcap_chunk_bytes)
    : dir_(dir), storage_(storage) {
  if (storage != "mcap" && storage != "sqlite3") throw std::invalid_argument("rosbag2: storage '" + storage + "' unknown");
  std::error_code ec;
  fs::create_directories(dir, ec);
  if (ec) throw std::runtime_error(dir + ": cannot create: " + ec.message());
  file_ = storage == "mcap" ? "rosbag2_0.mcap" : "rosbag2_0.db3";
  const std::string path = (fs::path(dir) / file_).string();
  if (fs::exists(path, ec)) throw std::runtime_error(path + ": exists already");
  if (storage == "mcap") out_ = std::make_unique<McapStorageWriter>(path, mcap_compression, mcap_chunk_bytes);
  else out_ = createSqlite3Storage(path);
}

Rosbag2Writer::~Rosbag2Writer() = default;

int Rosbag2Writer::addTopic(const std::string& name, const std::string& type, bool transient_local) {
  Topic t;
  t.name = name, t.type = type, t.qos = qosProfileYaml(transient_local);
  t.storage_id = out_->addTopic(name, type, t.qos);
  topics_.push_back(std::move(t));
  return static_cast<int>(topics_.size() - 1);
}

void Rosbag2Writer::write(int topic, std::uint64_t log_time_ns, const std::vector<std::uint8_t>& cdr) {
  Topic& t = topics_.at(static_cast<std::size_t>(topic));
  out_->write(t.storage_id, log_time_ns, cdr);
  ++t.messages;
  if (messages_++ == 0) first_ns_ = last_ns_ = log_time_ns;
  first_ns_ = std::min(first_ns_, log_time_ns);
  last_ns_ = std::max(last_ns_, log_time_ns);
}

void Rosbag2Writer::close() {
  if (closed_) return;
  closed_ = true;
  out_->close();
  const std::uint64_t duration = last_ns_ - first_ns_;
  std::ostringstream y;
  y << "rosbag2_bagfile_information:\n"
    << "  version: 5\n"
    << "  storage_identifier: " << storage_ << "\n"
    << "  duration:\n    nanoseconds: " << duration << "\n"
    << "  starting_time:\n    nanoseconds_since_epoch: " << first_ns_ << "\n"
    << "  message_count: " << messages_ << "\n"
    << "  topics_with_message_count:\n";
  for (const Topic& t : topics_)
    y << "    - topic_metadata:\n"
      << "        name: " << t.name << "\n"
      << "        type: " << t.type << "\n"
      << "        serialization_format: cdr\n"
      << "        offered_qos_profiles: " << quoted(t.qos) << "\n"
      << "      message_count: " << t.messages << "\n";
  y << "  compression_format: \"\"\n"
    << "  compression_mode: \"\"\n"
    << "  relative_file_paths:\n    - " << file_ << "\n"
    << "  files:\n"
    << "    - path: " << file_ << "\n"
    << "      starting_time:\n        nanoseconds_since_epoch: " << first_ns_ << "\n"
    << "      duration:\n        nanoseconds: " << duration << "\n"
    << "      message_count: " << messages_ << "\n";
  const std::string path = (fs::path(dir_) / "metadata.yaml").string();
  std::ofstream out(path);
  out << y.str();
  if (!out.flush()) throw std::runtime_error(path + ": cannot write");
}

}  // namespace bimloc::sim::ros2
