#include "sim/dataset/localized_bag_writer.hpp"

#include "sim/dataset/tum_writer.hpp"

#include <geometry_msgs/PoseWithCovarianceStamped.h>
#include <rosbag/bag.h>
#include <rosbag/view.h>
#include <tf2_msgs/TFMessage.h>

#include <stdexcept>

namespace bimloc::sim {

struct LocalizedBagWriter::Impl {
  std::string path, map_frame, odom_frame, base_frame, tf_topic;
  rosbag::Bag bag;
  std::uint32_t seq = 0;
};

LocalizedBagWriter::LocalizedBagWriter(const std::string& path, const std::string& input_bag, std::string map_frame,
                                       std::string odom_frame, std::string base_frame, std::string tf_topic)
    : impl_(std::make_unique<Impl>()) {
  impl_->path = path;
  impl_->map_frame = std::move(map_frame), impl_->odom_frame = std::move(odom_frame);
  impl_->base_frame = std::move(base_frame), impl_->tf_topic = std::move(tf_topic);
  try {
    impl_->bag.open(path, rosbag::bagmode::Write);
    rosbag::Bag in(input_bag, rosbag::bagmode::Read);
    // Copied as stored (serialised bytes and connection headers): no type needs to be known.
    for (const rosbag::MessageInstance& m : rosbag::View(in))
      impl_->bag.write(m.getTopic(), m.getTime(), m, m.getConnectionHeader());
  } catch (const std::exception& e) {
    throw std::runtime_error(path + ": cannot write the bag (copying " + input_bag + "): " + e.what());
  }
}

LocalizedBagWriter::~LocalizedBagWriter() {
  try {
    impl_->bag.close();
  } catch (...) {  // a bag being thrown away (its staging folder goes with it)
  }
}

void LocalizedBagWriter::add(double stamp_s, const Eigen::Isometry3d& T_map_odom, const Eigen::Isometry3d& T_map_base,
                             const Eigen::Matrix3d& covariance_xy_yaw) {
  ros::Time stamp;
  stamp.fromSec(stamp_s);
  const Eigen::Quaterniond q_odom = canonicalRotation(T_map_odom), q_base = canonicalRotation(T_map_base);

  tf2_msgs::TFMessage tf;
  geometry_msgs::TransformStamped t;
  t.header.stamp = stamp;
  t.header.frame_id = impl_->map_frame;
  t.child_frame_id = impl_->odom_frame;
  t.transform.translation.x = T_map_odom.translation().x();
  t.transform.translation.y = T_map_odom.translation().y();
  t.transform.translation.z = T_map_odom.translation().z();
  t.transform.rotation.x = q_odom.x(), t.transform.rotation.y = q_odom.y();
  t.transform.rotation.z = q_odom.z(), t.transform.rotation.w = q_odom.w();
  tf.transforms.push_back(t);

  geometry_msgs::PoseWithCovarianceStamped pose;
  pose.header.seq = impl_->seq++;
  pose.header.stamp = stamp;
  pose.header.frame_id = impl_->map_frame;
  pose.pose.pose.position.x = T_map_base.translation().x();
  pose.pose.pose.position.y = T_map_base.translation().y();
  pose.pose.pose.position.z = T_map_base.translation().z();
  pose.pose.pose.orientation.x = q_base.x(), pose.pose.pose.orientation.y = q_base.y();
  pose.pose.pose.orientation.z = q_base.z(), pose.pose.pose.orientation.w = q_base.w();
  // (x, y, yaw) -> rows/columns 0, 1, 5 of the row-major 6x6 (x y z roll pitch yaw).
  const int index[3] = {0, 1, 5};
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) pose.pose.covariance[index[i] * 6 + index[j]] = covariance_xy_yaw(i, j);
  try {
    impl_->bag.write(impl_->tf_topic, stamp, tf);
    impl_->bag.write(kLocalizationTopic, stamp, pose);
  } catch (const std::exception& e) {
    throw std::runtime_error(impl_->path + ": cannot write: " + e.what());
  }
}

void LocalizedBagWriter::close() {
  try {
    impl_->bag.close();
  } catch (const std::exception& e) {
    throw std::runtime_error(impl_->path + ": cannot finish the bag: " + e.what());
  }
}

}  // namespace bimloc::sim
