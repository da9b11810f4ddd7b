#include "sim/dataset/bag_reader.hpp"

#include "sim/dataset/bag_messages.hpp"
#include "sim/dataset/cloud_fields.hpp"
#include "sim/dataset/deskew.hpp"
#include "sim/dataset/recording_checks.hpp"
#include "sim/dataset/velodyne_scan_points.hpp"
#include "sim/ros2/rosbag2_reader.hpp"

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
std::optional<Eigen::Isometry3d> sample(const BagPose& p, PoseSampleDrops& drops) {
  return checkedPose(p.x, p.y, p.z, p.qx, p.qy, p.qz, p.qw, drops);
}

// A fixed transform (the mount's chain): one sample, no stream to fall back on, so refused.
Eigen::Isometry3d fixedPose(const BagPose& p, const std::string& where) {
  PoseSampleDrops drops;
  const auto T = sample(p, drops);
  if (!T) throw std::runtime_error(where + ": a pose that is not finite or whose quaternion does not have unit norm");
  return *T;
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

}  // namespace

CloudPoints decodeBagCloud(const BagCloud& cloud, const std::string& where) {
  if (cloud.packets.empty()) return decodeCloud(cloud.layout, cloud.bytes(), cloud.byteCount(), where);
  std::vector<RawPacket> raw;
  raw.reserve(cloud.packets.size());
  for (const BagPacket& p : cloud.packets) raw.push_back({p.stamp_s, p.data.data(), p.data.size()});
  return decodeVelodyneScan(raw, cloud.stamp_s, Vlp16DecodeOptions{}, where);
}

struct BagInput::Impl {
  std::unique_ptr<BagMessages> bag;
};

bool isRosBag(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  char magic[13] = {};
  return in.read(magic, 12) && std::string(magic) == "#ROSBAG V2.0";
}

BagInput::~BagInput() = default;

std::vector<std::string> BagInput::warnings() const { return impl_->bag->warnings(); }

std::string BagInput::topicList() const {
  std::ostringstream out;
  for (const auto& [topic, info] : impl_->bag->topics())
    out << "\n  " << topic << " (" << info.type << ", " << info.messages << " messages)";
  if (impl_->bag->topics().empty()) out << "\n  (none)";
  return out.str();
}

BagInput::BagInput(const std::string& path, const BagInputOptions& options)
    : impl_(std::make_unique<Impl>()), path_(path), options_(options) {
  auto fail = [&](const std::string& what) { throw std::runtime_error(path + ": " + what); };
  {
    if (isRosBag(path)) {
      impl_->bag = openRos1Bag(path);
    } else if (ros2::isRosbag2(path)) {
      impl_->bag = openRos2Bag(path);
    } else {
      fail("neither a ROS 1 bag (no '#ROSBAG V2.0' at its start) nor a ROS 2 bag (a folder with metadata.yaml, an .mcap or .db3 file)");
    }
    BagMessages& bag = *impl_->bag;
    const auto& topics = bag.topics();
    // Raw packets of another lidar (a Hesai's pandar_msgs, say): said, so that the user records
    // the driver's clouds instead.
    auto undecodedPackets = [&] {
      std::string found;
      for (const auto& [name, info] : topics)
        if ((info.type.find("Packet") != std::string::npos || info.type.find("PandarScan") != std::string::npos) &&
            info.type != bag.typeName(BagMessageKind::kVelodyneScan))
          found += (found.empty() ? "" : ", ") + name + " (" + info.type + ")";
      return found.empty() ? found
                           : "; " + found + " holds raw packets bimloc does not decode (it decodes the VLP-16's): record "
                             "the driver's sensor_msgs PointCloud2";
    };
    auto require = [&](const std::string& topic, std::vector<BagMessageKind> kinds, const std::string& option) {
      std::string types;
      for (const auto kind : kinds) types += (types.empty() ? "" : " or ") + bag.typeName(kind);
      const auto it = topics.find(topic);
      if (it == topics.end())
        fail("no topic " + topic + " (" + types + "; choose another with " + option + ")" + undecodedPackets() +
             ". The bag has:" + topicList());
      for (const auto kind : kinds)
        if (it->second.type == bag.typeName(kind)) return;
      fail("topic " + topic + " is " + it->second.type + ", not " + types + " (choose another with " + option +
           "). The bag has:" + topicList());
    };
    // The clouds: a driver's PointCloud2, or the VLP-16's raw packets, decoded here.
    require(options.cloud_topic, {BagMessageKind::kPointCloud2, BagMessageKind::kVelodyneScan}, "--cloud-topic");
    packets_ = bag.hasTopic(options.cloud_topic, BagMessageKind::kVelodyneScan);
    const bool odom_topic = topics.count(options.odom_topic) > 0;
    if (odom_topic || options.odom_topic_given) require(options.odom_topic, {BagMessageKind::kOdometry}, "--odom-topic");

    // /tf and /tf_static: the odometry transform over time, and the fixed edges for the mount.
    std::map<std::string, std::vector<Edge>> edges;
    std::set<std::pair<std::string, std::string>> seen;
    std::set<std::string> frames;
    std::map<std::string, std::vector<StampedPose>> from_odom;  // odom -> child, over time
    std::map<std::string, PoseSampleDrops> from_odom_drops;
    std::vector<std::string> tf_topics;
    for (const auto& t : {options.tf_static_topic, options.tf_topic})
      if (bag.hasTopic(t, BagMessageKind::kTFMessage)) tf_topics.push_back(t);
    // /tf_static first: its edges win over the same edge repeated on /tf.
    for (const auto& topic : tf_topics) {
      bag.forEachTransform(topic, [&](const BagTransform& t) {
        const std::string parent = frameName(t.parent), child = frameName(t.child);
        frames.insert(parent), frames.insert(child);
        const std::string where = path + ": " + topic + " " + parent + " -> " + child;
        if (parent == options.odom_frame) {  // the odometry: never a fixed edge
          if (const auto T = sample(t.pose, from_odom_drops[child])) from_odom[child].push_back({t.stamp_s, *T});
          return;
        }
        if (!seen.insert({parent, child}).second) return;
        const Eigen::Isometry3d T = fixedPose(t.pose, where);
        edges[parent].push_back({child, T});
        edges[child].push_back({parent, T.inverse()});
      });
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
      bag.forEachPose(options.odom_topic, [&](const BagStampedPose& p) {
        if (const auto T = sample(p.pose, odometry_drops_)) odometry_.push_back({p.stamp_s, *T});
      });
      odometry_source_ = options.odom_topic + " (" + bag.typeName(BagMessageKind::kOdometry) + ")";
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
      fail("no odometry: no topic " + options.odom_topic + " (" + bag.typeName(BagMessageKind::kOdometry) + "; choose it with --odom-topic) and no " +
           options.tf_topic + " transform " + options.odom_frame + " -> " + options.base_frame +
           " (choose the frames with --odom-frame, --base-frame). The bag has:" + topicList());

    if (bag.hasTopic(options.truth_topic, BagMessageKind::kOdometry) || bag.hasTopic(options.truth_topic, BagMessageKind::kPoseStamped)) {
      bag.forEachPose(options.truth_topic, [&](const BagStampedPose& p) {
        if (const auto T = sample(p.pose, truth_drops_)) ground_truth_.push_back({p.stamp_s, *T});
      });
      sortByStamp(ground_truth_);
    }

    // The clouds: their frame, the turn period (the median spacing of the recording times: a
    // Velodyne sends one cloud a turn at a fixed rpm), and whether the points carry `time`.
    const std::vector<double> received = bag.receiveTimes(options.cloud_topic);
    turns_ = received.size();
    if (turns_ == 0) fail("topic " + options.cloud_topic + " has no messages");
    std::vector<double> gaps;
    for (std::size_t i = 1; i < received.size(); ++i)
      if (received[i] > received[i - 1]) gaps.push_back(received[i] - received[i - 1]);
    if (!gaps.empty()) {
      std::nth_element(gaps.begin(), gaps.begin() + gaps.size() / 2, gaps.end());
      turn_period_s_ = gaps[gaps.size() / 2];
    }
    const std::shared_ptr<const BagCloud> first = bag.firstCloud(options.cloud_topic);
    if (!first) fail(options.cloud_topic + ": the first message cannot be read as " + bag.typeName(BagMessageKind::kPointCloud2));
    lidar_frame_ = frameName(first->frame_id);
    // The driver stamps a turn at its first firing (times >= 0) or, configured so, at its last
    // (times <= 0): the turn's middle is half a period after, or before, the stamp.
    CloudPoints p = decodeBagCloud(*first, path + ": " + options.cloud_topic + " message 0");
    makeTimesRelative(p, first->stamp_s);
    time_field_ = p.time_field;
    timed_ = !p.time_s.empty();
    double sum = 0;
    for (double t : p.time_s) sum += t;
    first_offset_s_ = !p.time_s.empty() && sum < 0 ? -0.5 * turn_period_s_ : 0.5 * turn_period_s_;
    first_turn_s_ = first->stamp_s + first_offset_s_;
    // Odometry outside the clouds' time (another clock: sim time against wall time) would make
    // every turn look taken from one pose: refused, as the dataset reader refuses it.
    const double c0 = first->stamp_s, c1 = c0 + turn_period_s_ * static_cast<double>(turns_);
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
  }
}

void BagInput::forEachTurn(const std::function<void(const BagTurn&)>& visit) const {
  std::size_t index = 0;
  double previous = -1e300;
  impl_->bag->forEachCloud(options_.cloud_topic, [&](std::shared_ptr<const BagCloud> cloud) {
    const std::string where = path_ + ": " + options_.cloud_topic + " message " + std::to_string(index);
    const double header_s = cloud->stamp_s;
    BagTurn turn;
    turn.index = index++;
    turn.stamp_s = header_s + first_offset_s_;
    if (!(turn.stamp_s > previous))
      throw std::runtime_error(where + ": stamp " + std::to_string(header_s) + " does not follow the previous cloud's");
    previous = turn.stamp_s;
    // Decoded and checked now (the bytes are in memory already): a scan with no usable point
    // is skipped before the localizer sees it. De-skewed only when the localizer asks.
    auto p = std::make_shared<CloudPoints>(decodeBagCloud(*cloud, where));
    PointDrops decoding;  // dropped by the decoder: not finite, and a packet decoder's range filter
    decoding.non_finite = p->non_finite;
    decoding.below_min_range = p->below_min_range, decoding.beyond_max_range = p->beyond_max_range;
    turn.drops = keepUsablePoints(p->xyz, &p->time_s, options_.range, decoding);
    turn.warnings = std::move(p->warnings);
    turn.points = [this, p, header_s, ref = turn.stamp_s] {
      if (options_.deskew && !p->time_s.empty()) {
        CloudPoints q;
        q.xyz = p->xyz;
        q.time_s = p->time_s;
        // Some drivers give absolute times (Hesai, RoboSense, Livox): make them relative.
        makeTimesRelative(q, header_s);
        deskew(q.xyz, q.time_s, header_s, ref, odometry_, T_base_lidar_);
        return q.xyz;
      }
      return p->xyz;
    };
    visit(turn);
    return true;
  });
}

}  // namespace bimloc::sim
