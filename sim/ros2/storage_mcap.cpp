// rosbag2's MCAP storage (rosbag2_storage_mcap, the default since Iron): a channel per topic,
// its schema named by the ROS type ("sensor_msgs/msg/PointCloud2"), message encoding "cdr",
// the QoS in the channel's metadata "offered_qos_profiles".
#include "sim/ros2/mcap_reader.hpp"
#include "sim/ros2/rosbag2_reader.hpp"

#include <map>
#include <set>

namespace bimloc::sim::ros2 {
namespace {

class McapStorage final : public Rosbag2Storage {
 public:
  explicit McapStorage(const std::string& path) : reader_(path) {
    std::map<std::string, std::size_t> by_name;
    for (const auto& [id, channel] : reader_.channels()) {
      const mcap::Schema* schema = reader_.schemaOf(channel);
      const auto count = reader_.messageCounts().find(id);
      const std::uint64_t n = count == reader_.messageCounts().end() ? 0 : count->second;
      const auto known = by_name.find(channel.topic);
      if (known != by_name.end()) {  // one topic on two channels (a second publisher's QoS)
        topics_[known->second].messages += n;
        channel_topic_[id] = known->second;
        continue;
      }
      BagTopic t;
      t.name = channel.topic;
      t.type = schema ? schema->name : "";
      if (schema) t.schema_encoding = schema->encoding, t.schema_data = schema->data;
      t.serialization_format = channel.message_encoding;
      const auto qos = channel.metadata.find("offered_qos_profiles");
      if (qos != channel.metadata.end()) t.offered_qos_profiles = qos->second;
      t.messages = n;
      by_name[t.name] = topics_.size();
      channel_topic_[id] = topics_.size();
      topics_.push_back(std::move(t));
    }
  }

  const std::vector<BagTopic>& topics() const override { return topics_; }
  const std::vector<std::string>& warnings() const override { return reader_.warnings(); }

  std::vector<std::uint64_t> logTimes(const std::string& topic) const override {
    std::set<std::uint16_t> ids;
    for (const auto& [id, index] : channel_topic_)
      if (topics_[index].name == topic) ids.insert(id);
    if (ids.empty()) return {};
    if (auto times = reader_.indexedLogTimes(ids)) return std::move(*times);
    return Rosbag2Storage::logTimes(topic);
  }

  void forEachMessage(const std::vector<std::string>& names, const std::function<void(const BagMessage&)>& visit,
                      ReadPlan plan) const override {
    std::set<std::uint16_t> wanted;
    for (const auto& [id, index] : channel_topic_)
      for (const auto& n : names)
        if (topics_[index].name == n) wanted.insert(id);
    if (!names.empty() && wanted.empty()) return;
    std::vector<std::uint64_t> seen(topics_.size(), 0);
    reader_.forEachMessage(wanted, [&](const McapMessage& m) {
      const std::size_t index = channel_topic_.at(m.channel->id);
      BagMessage b;
      b.topic = &topics_[index];
      b.log_time_ns = m.log_time_ns;
      b.data = m.data;
      b.size = m.size;
      b.where = reader_.path() + ": " + b.topic->name + " message " + std::to_string(seen[index]++);
      visit(b);
    }, plan);
  }

 private:
  McapReader reader_;
  std::vector<BagTopic> topics_;
  std::map<std::uint16_t, std::size_t> channel_topic_;
};

}  // namespace

std::unique_ptr<Rosbag2Storage> openMcapStorage(const std::string& path) { return std::make_unique<McapStorage>(path); }

}  // namespace bimloc::sim::ros2
