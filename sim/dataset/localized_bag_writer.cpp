#include "sim/dataset/localized_bag_writer.hpp"

#include "sim/dataset/ros_messages.hpp"

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
  tf2_msgs::TFMessage tf;
  tf.transforms.push_back(transformMessage(stamp, impl_->map_frame, impl_->odom_frame, T_map_odom));

  geometry_msgs::PoseWithCovarianceStamped pose;
  pose.header = header(stamp, impl_->seq++, impl_->map_frame);
  pose.pose.pose = poseMessage(T_map_base);
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
