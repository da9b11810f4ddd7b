// BagMessages of a ROS 2 bag: sim/ros2's rosbag2 reader and CDR decoding.
#include "sim/dataset/bag_messages.hpp"
#include "sim/dataset/velodyne_scan_cdr.hpp"

#include "sim/ros2/messages.hpp"
#include "sim/ros2/rosbag2_reader.hpp"

#include <stdexcept>

namespace bimloc::sim {
namespace {

BagPose bagPose(const ros2::Vector3& p, const ros2::Quaternion& q) { return {p.x, p.y, p.z, q.x, q.y, q.z, q.w}; }

class Ros2BagMessages final : public BagMessages {
 public:
  explicit Ros2BagMessages(const std::string& path) : reader_(path) {
    path_ = path;
    for (const auto& t : reader_.topics()) {
      topics_[t.name] = {t.type, static_cast<std::size_t>(t.messages)};
      if (t.serialization_format != "cdr" && !t.serialization_format.empty()) non_cdr_[t.name] = t.serialization_format;
    }
  }

  std::string format() const override { return "ROS 2 bag (" + reader_.storageIdentifier() + ")"; }

  std::string typeName(BagMessageKind kind) const override {
    switch (kind) {
      case BagMessageKind::kPointCloud2: return "sensor_msgs/msg/PointCloud2";
      case BagMessageKind::kOdometry: return "nav_msgs/msg/Odometry";
      case BagMessageKind::kTFMessage: return "tf2_msgs/msg/TFMessage";
      case BagMessageKind::kPoseStamped: return "geometry_msgs/msg/PoseStamped";
      case BagMessageKind::kVelodyneScan: return "velodyne_msgs/msg/VelodyneScan";
    }
    return "";
  }

  std::vector<std::string> warnings() const override { return reader_.warnings(); }

  void forEachTransform(const std::string& topic, const std::function<void(const BagTransform&)>& visit) const override {
    forEach(topic, [&](ros2::CdrReader& in, const ros2::BagMessage&) {
      for (const auto& t : ros2::readTFMessage(in).transforms)
        visit({t.header.stamp.seconds(), t.header.frame_id, t.child_frame_id, bagPose(t.transform.translation, t.transform.rotation)});
      return true;
    });
  }

  void forEachPose(const std::string& topic, const std::function<void(const BagStampedPose&)>& visit) const override {
    const bool stamped = hasTopic(topic, BagMessageKind::kPoseStamped);
    forEach(topic, [&](ros2::CdrReader& in, const ros2::BagMessage&) {
      if (stamped) {
        const auto p = ros2::readPoseStamped(in);
        visit({p.header.stamp.seconds(), bagPose(p.pose.position, p.pose.orientation)});
      } else {
        const auto o = ros2::readOdometry(in);
        visit({o.header.stamp.seconds(), bagPose(o.pose.pose.position, o.pose.pose.orientation)});
      }
      return true;
    });
  }

  std::vector<double> receiveTimes(const std::string& topic) const override {
    std::vector<double> times;
    for (const std::uint64_t ns : reader_.logTimes(topic)) times.push_back(1e-9 * static_cast<double>(ns));
    return times;
  }

  void forEachCloud(const std::string& topic, const std::function<bool(std::shared_ptr<const BagCloud>)>& visit) const override {
    clouds(topic, visit, ros2::ReadPlan::kAll);
  }

  std::shared_ptr<const BagCloud> firstCloud(const std::string& topic) const override {
    std::shared_ptr<const BagCloud> first;
    clouds(topic, [&](std::shared_ptr<const BagCloud> c) {
      first = std::make_shared<const BagCloud>(c->owned());  // kept past the visit
      return false;
    }, ros2::ReadPlan::kFirst);
    return first;
  }

 private:
  void clouds(const std::string& topic, const std::function<bool(std::shared_ptr<const BagCloud>)>& visit, ros2::ReadPlan plan) const {
    const bool packets = hasTopic(topic, BagMessageKind::kVelodyneScan);
    forEach(topic, [&](ros2::CdrReader& in, const ros2::BagMessage&) {
      if (packets) {
        const VelodyneScanView scan = readVelodyneScanCdr(in);
        auto out = std::make_shared<BagCloud>();
        out->stamp_s = scan.header_s;
        out->frame_id = scan.frame_id;
        for (const auto& p : scan.packets) out->packets.push_back({p.stamp_s, {p.data, p.data + p.size}});
        return visit(out);
      }
      // The points' bytes are lent, not copied: BagInput decodes them during the visit.
      auto out = std::make_shared<BagCloud>();
      const ros2::PointCloud2 c = ros2::readPointCloud2(in, out->lent, out->lent_size);
      out->stamp_s = c.header.stamp.seconds();
      out->frame_id = c.header.frame_id;
      for (const auto& f : c.fields) out->layout.fields.push_back({f.name, f.offset, f.datatype, f.count});
      out->layout.width = c.width, out->layout.height = c.height, out->layout.point_step = c.point_step;
      out->layout.row_step = c.row_step, out->layout.is_bigendian = c.is_bigendian;
      return visit(out);
    }, plan);
  }

  struct Stored {  // a message of a small topic, kept after the one pass that reads them all
    std::uint64_t log_time_ns;
    std::vector<std::uint8_t> data;
    std::string where;
  };

  // Decodes each message of `topic` as CDR; `decode` returns false to stop.
  void forEach(const std::string& topic, const std::function<bool(ros2::CdrReader&, const ros2::BagMessage&)>& decode,
               ros2::ReadPlan plan = ros2::ReadPlan::kAll) const {
    if (const auto it = non_cdr_.find(topic); it != non_cdr_.end())
      throw std::runtime_error(path_ + ": topic " + topic + " is serialized as '" + it->second + "', not cdr");
    struct Stop {};
    const auto one = [&](const ros2::BagMessage& m) {
      ros2::CdrReader in(m.data, m.size, m.where);
      const bool more = decode(in, m);
      // Fast-CDR pads a message to 4 bytes; more left over means bytes of another type.
      if (in.remaining() > 3)
        in.fail(std::to_string(in.remaining()) + " bytes left after the end of a " + m.topic->type + ": not of that type");
      if (!more) throw Stop{};
    };
    try {
      if (isSmall(topic)) {
        fillSmallTopics();
        for (const Stored& s : small_.at(topic)) {
          ros2::BagMessage m;
          m.topic = reader_.topic(topic);
          m.log_time_ns = s.log_time_ns, m.data = s.data.data(), m.size = s.data.size(), m.where = s.where;
          one(m);
        }
      } else {
        reader_.forEachMessage({topic}, one, plan);
      }
    } catch (const Stop&) {
    }
  }

  // The odometry, tf and pose topics are read by BagInput one after the other; in a bag whose
  // chunks mix every topic (MCAP as rosbag2 writes it), each would decompress the whole file.
  // One pass keeps them all (they are small beside the clouds), and decompresses a chunk only
  // as far as its last message of them: the clouds after it are left to the clouds' pass, which
  // reads every chunk with a cloud whole (and checks its CRC).
  bool isSmall(const std::string& topic) const {
    for (const auto kind : {BagMessageKind::kOdometry, BagMessageKind::kTFMessage, BagMessageKind::kPoseStamped})
      if (hasTopic(topic, kind)) return true;
    return false;
  }
  void fillSmallTopics() const {
    if (small_filled_) return;
    std::vector<std::string> topics;
    for (const auto& [name, info] : topics_)
      if (isSmall(name)) topics.push_back(name), small_[name];
    reader_.forEachMessage(topics, [&](const ros2::BagMessage& m) {
      small_[m.topic->name].push_back({m.log_time_ns, std::vector<std::uint8_t>(m.data, m.data + m.size), m.where});
    }, ros2::ReadPlan::kSmallTopics);  // in a bag whose chunks mix the clouds in, their prefixes only
    small_filled_ = true;
  }

  ros2::Rosbag2Reader reader_;
  std::map<std::string, std::string> non_cdr_;
  mutable std::map<std::string, std::vector<Stored>> small_;
  mutable bool small_filled_ = false;
};

}  // namespace

std::unique_ptr<BagMessages> openRos2Bag(const std::string& path) { return std::make_unique<Ros2BagMessages>(path); }

}  // namespace bimloc::sim
