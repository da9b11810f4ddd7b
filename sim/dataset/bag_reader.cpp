#include "sim/dataset/bag_reader.hpp"

#include "sim/dataset/cloud_fields.hpp"
#include "sim/dataset/deskew.hpp"
#include "sim/dataset/recording_checks.hpp"

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

// A sample of a stream (odometry, ground truth): dropped and counted when it is no pose.
std::optional<Eigen::Isometry3d> sample(const geometry_msgs::Pose& p, PoseSampleDrops& drops) {
  return checkedPose(p.position.x, p.position.y, p.position.z, p.orientation.x, p.orientation.y, p.orientation.z,
                     p.orientation.w, drops);
}

std::optional<Eigen::Isometry3d> sample(const geometry_msgs::Transform& t, PoseSampleDrops& drops) {
  return checkedPose(t.translation.x, t.translation.y, t.translation.z, t.rotation.x, t.rotation.y, t.rotation.z,
                     t.rotation.w, drops);
}

// A fixed transform (the mount's chain): one sample, no stream to fall back on, so refused.
Eigen::Isometry3d fixedPose(const geometry_msgs::Transform& t, const std::string& where) {
  PoseSampleDrops drops;
  const auto T = sample(t, drops);
  if (!T) throw std::runtime_error(where + ": a pose that is not finite or whose quaternion does not have unit norm");
  return *T;
}

CloudLayout layoutOf(const sensor_msgs::PointCloud2& cloud) {
  CloudLayout layout;
  for (const auto& f : cloud.fields) layout.fields.push_back({f.name, f.offset, f.datatype, f.count});
  layout.width = cloud.width, layout.height = cloud.height, layout.point_step = cloud.point_step;
  layout.row_step = cloud.row_step, layout.is_bigendian = cloud.is_bigendian;
  return layout;
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
      if (it->second.first != type)
        fail("topic " + topic + " is " + it->second.first + ", not " + type + " (choose another with " + option +
             "). The bag has:" + topicList());
    };
    require(options.cloud_topic, "sensor_msgs/PointCloud2", "--cloud-topic");
    const bool odom_topic = impl_->topics.count(options.odom_topic) > 0;
    if (odom_topic || options.odom_topic_given) require(options.odom_topic, "nav_msgs/Odometry", "--odom-topic");

    // /tf and /tf_static: the odometry transform over time, and the fixed edges for the mount.
    std::map<std::string, std::vector<Edge>> edges;
    std::set<std::pair<std::string, std::string>> seen;
    std::set<std::string> frames;
    std::map<std::string, std::vector<StampedPose>> from_odom;  // odom -> child, over time
    std::map<std::string, PoseSampleDrops> from_odom_drops;
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
            if (const auto T = sample(t.transform, from_odom_drops[child])) from_odom[child].push_back({t.header.stamp.toSec(), *T});
            continue;
          }
          if (!seen.insert({parent, child}).second) continue;
          const Eigen::Isometry3d T = fixedPose(t.transform, where);
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
        if (!odom) continue;
        if (const auto T = sample(odom->pose.pose, odometry_drops_)) odometry_.push_back({odom->header.stamp.toSec(), *T});
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
        odometry_drops_ = from_odom_drops[child];
        odometry_source_ = options.tf_topic + " " + options.odom_frame + " -> " + options.base_frame +
                           (child == options.base_frame ? "" : " (via " + child + ")");
        break;
      }
    }
    // Any sample that came through from /tf of an unusable stream: counted all the same.
    if (odometry_.empty())
      for (const auto& [child, drops] : from_odom_drops)
        if (child == options.base_frame || fixed(child, options.base_frame)) odometry_drops_ = drops;
    sortByStamp(odometry_);
    if (odometry_.empty() && odometry_drops_.read > 0)
      fail("no odometry: all " + std::to_string(odometry_drops_.read) + " samples of " +
           (odom_topic ? options.odom_topic : options.tf_topic + " " + options.odom_frame + " -> " + options.base_frame) +
           " are no pose (" + std::to_string(odometry_drops_.non_finite) + " not finite, " +
           std::to_string(odometry_drops_.zero_quaternion) + " with a zero quaternion, " +
           std::to_string(odometry_drops_.not_unit_quaternion) + " with a quaternion not of unit norm)");
    if (odometry_.empty())
      fail("no odometry: no topic " + options.odom_topic + " (nav_msgs/Odometry; choose it with --odom-topic) and no " +
           options.tf_topic + " transform " + options.odom_frame + " -> " + options.base_frame +
           " (choose the frames with --odom-frame, --base-frame). The bag has:" + topicList());

    if (impl_->topics.count(options.truth_topic) && impl_->topics[options.truth_topic].first == "nav_msgs/Odometry") {
      for (const rosbag::MessageInstance& m : rosbag::View(impl_->bag, rosbag::TopicQuery(options.truth_topic))) {
        const auto truth = m.instantiate<nav_msgs::Odometry>();
        if (!truth) continue;
        if (const auto T = sample(truth->pose.pose, truth_drops_)) ground_truth_.push_back({truth->header.stamp.toSec(), *T});
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
    const auto first = clouds.begin()->instantiate<sensor_msgs::PointCloud2>();
    if (!first) fail(options.cloud_topic + ": the first message cannot be read as sensor_msgs/PointCloud2");
    lidar_frame_ = frameName(first->header.frame_id);
    bool has_time = false;
    for (const auto& f : first->fields) has_time = has_time || f.name == "time";
    timed_ = has_time;
    // The driver stamps a turn at its first firing (times >= 0) or, configured so, at its last
    // (times <= 0): the turn's middle is half a period after, or before, the stamp.
    if (has_time) {
      const CloudPoints p = decodeCloud(layoutOf(*first), first->data.data(), first->data.size(),
                                        path + ": " + options.cloud_topic + " message 0");
      double sum = 0;
      for (double t : p.time_s) sum += t;
      first_offset_s_ = !p.time_s.empty() && sum < 0 ? -0.5 * turn_period_s_ : 0.5 * turn_period_s_;
    } else {
      first_offset_s_ = 0.5 * turn_period_s_;
    }
    first_turn_s_ = first->header.stamp.toSec() + first_offset_s_;
    // Odometry outside the clouds' time (another clock: sim time against wall time) would make
    // every turn look taken from one pose: refused, as the dataset reader refuses it.
    const double c0 = first->header.stamp.toSec(), c1 = c0 + turn_period_s_ * static_cast<double>(turns_);
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
      const auto cloud = m.instantiate<sensor_msgs::PointCloud2>();
      if (!cloud) throw std::runtime_error(where + ": cannot be read as sensor_msgs/PointCloud2");
      const double header_s = cloud->header.stamp.toSec();
      BagTurn turn;
      turn.index = index++;
      turn.stamp_s = header_s + first_offset_s_;
      if (!(turn.stamp_s > previous))
        throw std::runtime_error(where + ": stamp " + std::to_string(header_s) + " does not follow the previous cloud's");
      previous = turn.stamp_s;
      // Decoded and checked now (the bytes are in memory already): a scan with no usable point
      // is skipped before the localizer sees it. De-skewed only when the localizer asks.
      auto p = std::make_shared<CloudPoints>(decodeCloud(layoutOf(*cloud), cloud->data.data(), cloud->data.size(), where));
      turn.drops = keepUsablePoints(p->xyz, &p->time_s, options_.range, p->non_finite);
      turn.warnings = std::move(p->warnings);
      turn.points = [this, p, header_s, ref = turn.stamp_s] {
        if (options_.deskew && !p->time_s.empty()) {
          std::vector<Eigen::Vector3f> xyz = p->xyz;
          std::vector<double> time_s = p->time_s;
          // Some drivers give absolute times (seconds since the epoch): make them relative.
          if (std::abs(time_s.front()) > 1e6)
            for (double& t : time_s) t -= header_s;
          deskew(xyz, time_s, header_s, ref, odometry_, T_base_lidar_);
          return xyz;
        }
        return p->xyz;
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
