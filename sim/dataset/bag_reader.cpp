#include "sim/dataset/bag_reader.hpp"

#include "sim/dataset/cloud_fields.hpp"
#include "sim/dataset/deskew.hpp"
#include "sim/dataset/velodyne_scan_msg.hpp"
#include "sim/dataset/velodyne_scan_points.hpp"

#include <geometry_msgs/TransformStamped.h>
#include <nav_msgs/Odometry.h>
#include <rosbag/bag.h>
#include <rosbag/view.h>
#include <sensor_msgs/PointCloud2.h>
#include <tf2_msgs/TFMessage.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <map>
#include <queue>
#include <set>
#include <sstream>
#include <stdexcept>

namespace bimloc::sim {
namespace {

std::string frameName(std::string frame) {  // tf2 drops a leading '/' (tf1's style)
  if (!frame.empty() && frame.front() == '/') frame.erase(0, 1);
  return frame;
}

Eigen::Isometry3d pose(double x, double y, double z, double qx, double qy, double qz, double qw, const std::string& where) {
  const Eigen::Quaterniond q(qw, qx, qy, qz);
  if (!std::isfinite(q.norm()) || std::abs(q.norm() - 1.0) > 1e-3 || !std::isfinite(x + y + z))
    throw std::runtime_error(where + ": a pose that is not finite or whose quaternion does not have unit norm");
  Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
  T.linear() = q.normalized().toRotationMatrix();
  T.translation() = Eigen::Vector3d(x, y, z);
  return T;
}

Eigen::Isometry3d pose(const geometry_msgs::Pose& p, const std::string& where) {
  return pose(p.position.x, p.position.y, p.position.z, p.orientation.x, p.orientation.y, p.orientation.z,
              p.orientation.w, where);
}

Eigen::Isometry3d pose(const geometry_msgs::Transform& t, const std::string& where) {
  return pose(t.translation.x, t.translation.y, t.translation.z, t.rotation.x, t.rotation.y, t.rotation.z, t.rotation.w,
              where);
}

// Sorted by stamp, one sample per stamp (a bag may hold a message twice or out of order).
void sortByStamp(std::vector<StampedPose>& samples) {
  std::stable_sort(samples.begin(), samples.end(), [](const auto& a, const auto& b) { return a.stamp_s < b.stamp_s; });
  samples.erase(std::unique(samples.begin(), samples.end(), [](const auto& a, const auto& b) { return a.stamp_s == b.stamp_s; }),
                samples.end());
}

struct Edge {
  std::string to;
  Eigen::Isometry3d T;  // parent <- child, or its inverse when walked backwards
};

// rosbag's words, with what they mean for a recording: a bag cut short (the recorder killed)
// has no index at its end, which `rosbag reindex` rebuilds.
std::string bagProblem(const std::exception& e) {
  const std::string what = e.what();
  const bool cut = what.find("Error reading from file") != std::string::npos || what.find("unindexed") != std::string::npos;
  return "damaged or unreadable bag: " + what +
         (cut ? " (a bag cut short, e.g. a recording that did not finish: 'rosbag reindex' rebuilds its index)" : "");
}

constexpr const char* kCloudType = "sensor_msgs/PointCloud2";
constexpr const char* kPacketsType = "velodyne_msgs/VelodyneScan";

// One message of the cloud topic: its stamp and frame at once, its points when asked.
struct CloudMessage {
  double header_s = 0;
  std::string frame;
  std::function<CloudPoints()> points;
};

CloudMessage readCloudMessage(const rosbag::MessageInstance& m, bool packets, const std::string& where) {
  CloudMessage out;
  if (packets) {  // the VLP-16's raw packets, decoded as the manual says (vlp16_packet.hpp)
    const auto scan = m.instantiate<velodyne_msgs::VelodyneScan>();
    if (!scan) throw std::runtime_error(where + ": cannot be read as velodyne_msgs/VelodyneScan");
    out.header_s = scan->header.stamp.toSec();
    out.frame = frameName(scan->header.frame_id);
    out.points = [scan, where, header_s = out.header_s] {
      std::vector<RawPacket> raw;
      raw.reserve(scan->packets.size());
      for (const auto& packet : scan->packets) raw.push_back({packet.stamp.toSec(), packet.data.data(), packet.data.size()});
      return decodeVelodyneScan(raw, header_s, Vlp16DecodeOptions{}, where);
    };
    return out;
  }
  const auto cloud = m.instantiate<sensor_msgs::PointCloud2>();
  if (!cloud) throw std::runtime_error(where + ": cannot be read as sensor_msgs/PointCloud2");
  out.header_s = cloud->header.stamp.toSec();
  out.frame = frameName(cloud->header.frame_id);
  out.points = [cloud, where] {
    CloudLayout layout;
    for (const auto& f : cloud->fields) layout.fields.push_back({f.name, f.offset, f.datatype, f.count});
    layout.width = cloud->width, layout.height = cloud->height, layout.point_step = cloud->point_step;
    layout.row_step = cloud->row_step, layout.is_bigendian = cloud->is_bigendian;
    return decodeCloud(layout, cloud->data.data(), cloud->data.size(), where);
  };
  return out;
}

}  // namespace

struct BagInput::Impl {
  rosbag::Bag bag;
  std::map<std::string, std::pair<std::string, std::size_t>> topics;  // topic: (type, messages)
};

bool isRosBag(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  char magic[13] = {};
  return in.read(magic, 12) && std::string(magic) == "#ROSBAG V2.0";
}

BagInput::~BagInput() = default;

std::string BagInput::topicList() const {
  std::ostringstream out;
  for (const auto& [topic, info] : impl_->topics)
    out << "\n  " << topic << " (" << info.first << ", " << info.second << " messages)";
  if (impl_->topics.empty()) out << "\n  (none)";
  return out.str();
}

BagInput::BagInput(const std::string& path, const BagInputOptions& options)
    : impl_(std::make_unique<Impl>()), path_(path), options_(options) {
  auto fail = [&](const std::string& what) { throw std::runtime_error(path + ": " + what); };
  // rosbag's exceptions (and a damaged file's bad_alloc) name no file: every read is wrapped.
  try {
    if (!isRosBag(path)) fail("not a ROS1 bag (no '#ROSBAG V2.0' at its start)");
    impl_->bag.open(path, rosbag::bagmode::Read);
    rosbag::View all(impl_->bag);
    for (const rosbag::ConnectionInfo* c : all.getConnections()) impl_->topics[c->topic].first = c->datatype;
    for (auto& [topic, info] : impl_->topics) info.second = rosbag::View(impl_->bag, rosbag::TopicQuery(topic)).size();
    auto require = [&](const std::string& topic, const std::string& type, const std::string& option) {
      const auto it = impl_->topics.find(topic);
      if (it == impl_->topics.end())
        fail("no topic " + topic + " (" + type + "; choose another with " + option + "). The bag has:" + topicList());
      // `type` may name alternatives: "A or B".
      const std::string alternatives = " or " + type + " or ";
      if (alternatives.find(" or " + it->second.first + " or ") == std::string::npos)
        fail("topic " + topic + " is " + it->second.first + ", not " + type + " (choose another with " + option +
             "). The bag has:" + topicList());
    };
    // The clouds: a driver's PointCloud2, or the VLP-16's raw packets, decoded here.
    const auto cloud_it = impl_->topics.find(options.cloud_topic);
    packets_ = cloud_it != impl_->topics.end() && cloud_it->second.first == kPacketsType;
    require(options.cloud_topic, std::string(kCloudType) + " or " + kPacketsType, "--cloud-topic");
    const bool odom_topic = impl_->topics.count(options.odom_topic) > 0;
    if (odom_topic || options.odom_topic_given) require(options.odom_topic, "nav_msgs/Odometry", "--odom-topic");

    // /tf and /tf_static: the odometry transform over time, and the fixed edges for the mount.
    std::map<std::string, std::vector<Edge>> edges;
    std::set<std::pair<std::string, std::string>> seen;
    std::set<std::string> frames;
    std::map<std::string, std::vector<StampedPose>> from_odom;  // odom -> child, over time
    std::vector<std::string> tf_topics;
    for (const auto& t : {options.tf_static_topic, options.tf_topic})
      if (impl_->topics.count(t) && impl_->topics[t].first == "tf2_msgs/TFMessage") tf_topics.push_back(t);
    // /tf_static first: its edges win over the same edge repeated on /tf.
    for (const auto& topic : tf_topics) {
      for (const rosbag::MessageInstance& m : rosbag::View(impl_->bag, rosbag::TopicQuery(topic))) {
        const auto tf = m.instantiate<tf2_msgs::TFMessage>();
        if (!tf) continue;
        for (const auto& t : tf->transforms) {
          const std::string parent = frameName(t.header.frame_id), child = frameName(t.child_frame_id);
          frames.insert(parent), frames.insert(child);
          const std::string where = path + ": " + topic + " " + parent + " -> " + child;
          if (parent == options.odom_frame) {  // the odometry: never a fixed edge
            from_odom[child].push_back({t.header.stamp.toSec(), pose(t.transform, where)});
            continue;
          }
          if (!seen.insert({parent, child}).second) continue;
          const Eigen::Isometry3d T = pose(t.transform, where);
          edges[parent].push_back({child, T});
          edges[child].push_back({parent, T.inverse()});
        }
      }
    }

    // Breadth-first through the fixed transforms: T_from_to, when a chain links them.
    auto fixed = [&edges](const std::string& from, const std::string& to) -> std::optional<Eigen::Isometry3d> {
      std::map<std::string, Eigen::Isometry3d> reached{{from, Eigen::Isometry3d::Identity()}};
      std::queue<std::string> queue;
      queue.push(from);
      while (!queue.empty() && !reached.count(to)) {
        const std::string f = queue.front();
        queue.pop();
        for (const Edge& e : edges[f])
          if (!reached.count(e.to)) reached[e.to] = reached[f] * e.T, queue.push(e.to);
      }
      if (!reached.count(to)) return std::nullopt;
      return reached[to];
    };

    if (odom_topic) {
      for (const rosbag::MessageInstance& m : rosbag::View(impl_->bag, rosbag::TopicQuery(options.odom_topic))) {
        const auto odom = m.instantiate<nav_msgs::Odometry>();
        if (odom) odometry_.push_back({odom->header.stamp.toSec(), pose(odom->pose.pose, path + ": " + options.odom_topic)});
      }
      odometry_source_ = options.odom_topic + " (nav_msgs/Odometry)";
    } else {
      // odom -> base directly, or odom -> a frame fixed to base (base_footprint -> base_link).
      for (auto& [child, samples] : from_odom) {
        const auto T_child_base = child == options.base_frame ? std::optional(Eigen::Isometry3d::Identity())
                                                               : fixed(child, options.base_frame);
        if (!T_child_base) continue;
        for (auto& sample : samples) sample.pose = sample.pose * *T_child_base;
        odometry_ = std::move(samples);
        odometry_source_ = options.tf_topic + " " + options.odom_frame + " -> " + options.base_frame +
                           (child == options.base_frame ? "" : " (via " + child + ")");
        break;
      }
    }
    sortByStamp(odometry_);
    if (odometry_.empty())
      fail("no odometry: no topic " + options.odom_topic + " (nav_msgs/Odometry; choose it with --odom-topic) and no " +
           options.tf_topic + " transform " + options.odom_frame + " -> " + options.base_frame +
           " (choose the frames with --odom-frame, --base-frame). The bag has:" + topicList());

    if (impl_->topics.count(options.truth_topic) && impl_->topics[options.truth_topic].first == "nav_msgs/Odometry") {
      for (const rosbag::MessageInstance& m : rosbag::View(impl_->bag, rosbag::TopicQuery(options.truth_topic))) {
        const auto truth = m.instantiate<nav_msgs::Odometry>();
        if (truth) ground_truth_.push_back({truth->header.stamp.toSec(), pose(truth->pose.pose, path + ": " + options.truth_topic)});
      }
      sortByStamp(ground_truth_);
    }

    // The clouds: their frame, the turn period (the median spacing of the recording times: a
    // Velodyne sends one cloud a turn at a fixed rpm), and whether the points carry `time`.
    rosbag::View clouds(impl_->bag, rosbag::TopicQuery(options.cloud_topic));
    std::vector<double> received;
    for (const rosbag::MessageInstance& m : clouds) received.push_back(m.getTime().toSec());
    turns_ = received.size();
    if (turns_ == 0) fail("topic " + options.cloud_topic + " has no messages");
    std::vector<double> gaps;
    for (std::size_t i = 1; i < received.size(); ++i)
      if (received[i] > received[i - 1]) gaps.push_back(received[i] - received[i - 1]);
    if (!gaps.empty()) {
      std::nth_element(gaps.begin(), gaps.begin() + gaps.size() / 2, gaps.end());
      turn_period_s_ = gaps[gaps.size() / 2];
    }
    const CloudMessage first = readCloudMessage(*clouds.begin(), packets_, path + ": " + options.cloud_topic + " message 0");
    lidar_frame_ = first.frame;
    // The driver stamps a turn at its first firing (times >= 0) or, configured so, at its last
    // (times <= 0): the turn's middle is half a period after, or before, the stamp.
    const CloudPoints p = first.points();
    time_field_ = p.time_field;
    timed_ = !p.time_s.empty();
    double sum = 0;
    for (double t : p.time_s) sum += p.time_absolute ? t - first.header_s : t;
    first_offset_s_ = !p.time_s.empty() && sum < 0 ? -0.5 * turn_period_s_ : 0.5 * turn_period_s_;
    first_turn_s_ = first.header_s + first_offset_s_;
    // Odometry outside the clouds' time (another clock: sim time against wall time) would make
    // every turn look taken from one pose: refused, as the dataset reader refuses it.
    const double c0 = first.header_s, c1 = c0 + turn_period_s_ * static_cast<double>(turns_);
    if (odometry_.back().stamp_s < c0 || odometry_.front().stamp_s > c1) {
      char what[256];
      std::snprintf(what, sizeof what, "the clouds (%.3f to %.3f s) and the odometry (%.3f to %.3f s) never overlap in time",
                    c0, c1, odometry_.front().stamp_s, odometry_.back().stamp_s);
      fail(what);
    }

    if (options.mount) {
      T_base_lidar_ = *options.mount;
      mount_source_ = "--mount";
    } else if (lidar_frame_ == options.base_frame) {
      mount_source_ = "the clouds are in " + options.base_frame;
    } else {
      const auto mount = fixed(options.base_frame, lidar_frame_);  // base_link -> ... -> the cloud's frame
      if (!mount) {
        std::string known;
        for (const auto& f : frames) known += (known.empty() ? "" : ", ") + f;
        fail("no transform " + options.base_frame + " -> " + lidar_frame_ + " (the clouds' frame) in " +
             options.tf_static_topic + " or " + options.tf_topic + "; give the mount with --mount x,y,z,roll,pitch,yaw "
             "or the base frame with --base-frame. Frames in the bag's tf: " + (known.empty() ? "(none)" : known));
      }
      T_base_lidar_ = *mount;
      mount_source_ = "tf " + options.base_frame + " -> " + lidar_frame_;
    }
  } catch (const ros::Exception& e) {  // rosbag::BagException and the deserialiser's overruns
    fail(bagProblem(e));
  } catch (const std::bad_alloc&) {
    fail("damaged bag: a record claims more memory than there is");
  }
}

void BagInput::forEachTurn(const std::function<void(const BagTurn&)>& visit) const {
  try {
    rosbag::View clouds(impl_->bag, rosbag::TopicQuery(options_.cloud_topic));
    std::size_t index = 0;
    double previous = -1e300;
    for (const rosbag::MessageInstance& m : clouds) {
      const std::string where = path_ + ": " + options_.cloud_topic + " message " + std::to_string(index);
      const CloudMessage message = readCloudMessage(m, packets_, where);
      const double header_s = message.header_s;
      BagTurn turn;
      turn.index = index++;
      turn.stamp_s = header_s + first_offset_s_;
      if (!(turn.stamp_s > previous))
        throw std::runtime_error(where + ": stamp " + std::to_string(header_s) + " does not follow the previous cloud's");
      previous = turn.stamp_s;
      turn.points = [this, message, header_s, ref = turn.stamp_s] {
        CloudPoints p = message.points();
        if (options_.deskew && !p.time_s.empty()) {
          // Some drivers give absolute times (seconds since the epoch): make them relative.
          if (p.time_absolute)
            for (double& t : p.time_s) t -= header_s;
          deskew(p.xyz, p.time_s, header_s, ref, odometry_, T_base_lidar_);
        }
        return std::move(p.xyz);
      };
      visit(turn);
    }
  } catch (const ros::Exception& e) {
    throw std::runtime_error(path_ + ": " + bagProblem(e));
  } catch (const std::bad_alloc&) {
    throw std::runtime_error(path_ + ": damaged bag: a record claims more memory than there is");
  }
}

}  // namespace bimloc::sim
