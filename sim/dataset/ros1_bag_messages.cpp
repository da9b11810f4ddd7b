// BagMessages of a ROS 1 bag, through Debian's rosbag_storage and the ROS 1 message headers.
#include "sim/dataset/bag_messages.hpp"
#include "sim/dataset/ros1_bag_check.hpp"
#include "sim/dataset/velodyne_scan_msg.hpp"

#include <geometry_msgs/PoseStamped.h>
#include <nav_msgs/Odometry.h>
#include <rosbag/bag.h>
#include <rosbag/view.h>
#include <sensor_msgs/PointCloud2.h>
#include <tf2_msgs/TFMessage.h>

#include <fstream>
#include <map>
#include <set>
#include <stdexcept>

namespace bimloc::sim {
namespace {

// rosbag's words, with what they mean for a recording: a bag cut short (the recorder killed)
// has no index at its end, which `rosbag reindex` rebuilds.
std::string bagProblem(const std::exception& e) {
  const std::string what = e.what();
  const bool cut = what.find("Error reading from file") != std::string::npos || what.find("unindexed") != std::string::npos;
  return "damaged or unreadable bag: " + what +
         (cut ? " (a bag cut short, e.g. a recording that did not finish: 'rosbag reindex' rebuilds its index)" : "");
}

BagPose bagPose(const geometry_msgs::Pose& p) {
  return {p.position.x, p.position.y, p.position.z, p.orientation.x, p.orientation.y, p.orientation.z, p.orientation.w};
}

class Ros1BagMessages final : public BagMessages {
 public:
  explicit Ros1BagMessages(const std::string& path) {
    path_ = path;
    // What rosbag would read past its buffers on, refused first.
    for (Ros1ChunkEnd& end : checkRos1BagRecords(path)) ends_[{end.topic, end.stamp_ns}] = std::move(end);
    guarded([&] {
      bag_.open(path, rosbag::bagmode::Read);
      rosbag::View all(bag_);
      for (const rosbag::ConnectionInfo* c : all.getConnections()) topics_[c->topic].type = c->datatype;
      for (auto& [topic, info] : topics_) info.messages = rosbag::View(bag_, rosbag::TopicQuery(topic)).size();
    });
  }

  std::string format() const override { return "ROS 1 bag"; }

  std::vector<std::string> warnings() const override {
    if (oversized_.empty()) return {};
    return {std::to_string(oversized_.size()) + " compressed chunk(s) (the first at byte " + std::to_string(*oversized_.begin()) +
            ") declare more uncompressed bytes than their records hold: a wrong size field, read anyway (rosbag decompresses "
            "bz2 into a buffer of the declared size)"};
  }

  std::string typeName(BagMessageKind kind) const override {
    switch (kind) {
      case BagMessageKind::kPointCloud2: return "sensor_msgs/PointCloud2";
      case BagMessageKind::kOdometry: return "nav_msgs/Odometry";
      case BagMessageKind::kTFMessage: return "tf2_msgs/TFMessage";
      case BagMessageKind::kPoseStamped: return "geometry_msgs/PoseStamped";
      case BagMessageKind::kVelodyneScan: return "velodyne_msgs/VelodyneScan";
    }
    return "";
  }

  void forEachTransform(const std::string& topic, const std::function<void(const BagTransform&)>& visit) const override {
    guarded([&] {
      for (const rosbag::MessageInstance& m : rosbag::View(bag_, rosbag::TopicQuery(topic))) {
        const auto tf = m.instantiate<tf2_msgs::TFMessage>();
        if (!tf) continue;
        checkEnd(m);
        for (const auto& t : tf->transforms) {
          const auto& r = t.transform.rotation;
          const auto& p = t.transform.translation;
          visit({t.header.stamp.toSec(), t.header.frame_id, t.child_frame_id, {p.x, p.y, p.z, r.x, r.y, r.z, r.w}});
        }
      }
    });
  }

  void forEachPose(const std::string& topic, const std::function<void(const BagStampedPose&)>& visit) const override {
    guarded([&] {
      const bool stamped = hasTopic(topic, BagMessageKind::kPoseStamped);
      for (const rosbag::MessageInstance& m : rosbag::View(bag_, rosbag::TopicQuery(topic))) {
        checkEnd(m);
        if (stamped) {
          if (const auto p = m.instantiate<geometry_msgs::PoseStamped>()) visit({p->header.stamp.toSec(), bagPose(p->pose)});
        } else if (const auto odom = m.instantiate<nav_msgs::Odometry>()) {
          visit({odom->header.stamp.toSec(), bagPose(odom->pose.pose)});
        }
      }
    });
  }

  std::vector<double> receiveTimes(const std::string& topic) const override {
    std::vector<double> times;
    guarded([&] {
      for (const rosbag::MessageInstance& m : rosbag::View(bag_, rosbag::TopicQuery(topic))) times.push_back(m.getTime().toSec());
    });
    return times;
  }

  void forEachCloud(const std::string& topic, const std::function<bool(std::shared_ptr<const BagCloud>)>& visit) const override {
    const bool packets = hasTopic(topic, BagMessageKind::kVelodyneScan);
    guarded([&] {
      std::size_t index = 0;
      for (const rosbag::MessageInstance& m : rosbag::View(bag_, rosbag::TopicQuery(topic))) {
        checkEnd(m);
        if (packets) {
          const auto scan = m.instantiate<velodyne_msgs::VelodyneScan>();
          if (!scan)
            throw std::runtime_error(path_ + ": " + topic + " message " + std::to_string(index) + ": cannot be read as velodyne_msgs/VelodyneScan");
          ++index;
          auto out = std::make_shared<BagCloud>();
          out->stamp_s = scan->header.stamp.toSec();
          out->frame_id = scan->header.frame_id;
          for (const auto& p : scan->packets) out->packets.push_back({p.stamp.toSec(), {p.data.begin(), p.data.end()}});
          if (!visit(out)) break;
          continue;
        }
        const auto cloud = m.instantiate<sensor_msgs::PointCloud2>();
        if (!cloud)
          throw std::runtime_error(path_ + ": " + topic + " message " + std::to_string(index) + ": cannot be read as sensor_msgs/PointCloud2");
        ++index;
        auto out = std::make_shared<BagCloud>();
        out->stamp_s = cloud->header.stamp.toSec();
        out->frame_id = cloud->header.frame_id;
        for (const auto& f : cloud->fields) out->layout.fields.push_back({f.name, f.offset, f.datatype, f.count});
        out->layout.width = cloud->width, out->layout.height = cloud->height, out->layout.point_step = cloud->point_step;
        out->layout.row_step = cloud->row_step, out->layout.is_bigendian = cloud->is_bigendian;
        out->data = std::move(const_cast<sensor_msgs::PointCloud2&>(*cloud).data);
        if (!visit(out)) break;
      }
    });
  }

 private:
  // rosbag's exceptions (and a damaged file's bad_alloc) name no file: every read is wrapped.
  template <typename F>
  void guarded(F&& f) const {
    try {
      f();
    } catch (const ros::Exception& e) {  // rosbag::BagException and the deserialiser's overruns
      throw std::runtime_error(path_ + ": " + bagProblem(e));
    } catch (const std::bad_alloc&) {
      throw std::runtime_error(path_ + ": damaged bag: a record claims more memory than there is");
    }
  }

  // A message that ends a compressed chunk: its record (4 + the 38 bytes of its header, op,
  // conn and time, as rosbag writes it + 4 + its data) must end at the chunk's size field.
  void checkEnd(const rosbag::MessageInstance& m) const {
    if (ends_.empty()) return;
    const auto it = ends_.find({m.getTopic(), m.getTime().toNSec()});
    if (it == ends_.end()) return;
    constexpr std::uint64_t kRecordBytes = 4 + 38 + 4;
    if (std::uint64_t{it->second.last_offset} + kRecordBytes + m.size() < it->second.size) oversized_.insert(it->second.chunk_pos);
  }

  mutable rosbag::Bag bag_;
  std::map<std::pair<std::string, std::uint64_t>, Ros1ChunkEnd> ends_;
  mutable std::set<std::uint64_t> oversized_;  // the chunks found so, by position
};

}  // namespace

bool BagMessages::hasTopic(const std::string& topic, BagMessageKind kind) const {
  const auto it = topics_.find(topic);
  return it != topics_.end() && it->second.type == typeName(kind);
}

std::shared_ptr<const BagCloud> BagMessages::firstCloud(const std::string& topic) const {
  std::shared_ptr<const BagCloud> first;
  forEachCloud(topic, [&](std::shared_ptr<const BagCloud> c) {
    first = std::make_shared<const BagCloud>(c->owned());  // kept past the visit
    return false;
  });
  return first;
}

std::unique_ptr<BagMessages> openRos1Bag(const std::string& path) { return std::make_unique<Ros1BagMessages>(path); }

}  // namespace bimloc::sim
