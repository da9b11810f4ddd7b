#include "sim/dataset/ros_messages.hpp"

#include "sim/dataset/tum_writer.hpp"

namespace bimloc::sim {

ros::Time rosTime(std::uint64_t stamp_ns) {
  ros::Time t;
  t.fromNSec(stamp_ns);
  return t;
}

std_msgs::Header header(const ros::Time& stamp, std::uint32_t seq, const std::string& frame_id) {
  std_msgs::Header h;
  h.seq = seq;
  h.stamp = stamp;
  h.frame_id = frame_id;
  return h;
}

geometry_msgs::Pose poseMessage(const Eigen::Isometry3d& T) {
  geometry_msgs::Pose pose;
  pose.position.x = T.translation().x();
  pose.position.y = T.translation().y();
  pose.position.z = T.translation().z();
  const Eigen::Quaterniond q = canonicalRotation(T);
  pose.orientation.x = q.x();
  pose.orientation.y = q.y();
  pose.orientation.z = q.z();
  pose.orientation.w = q.w();
  return pose;
}

geometry_msgs::TransformStamped transformMessage(const ros::Time& stamp, const std::string& parent, const std::string& child,
                                                 const Eigen::Isometry3d& T_parent_child) {
  geometry_msgs::TransformStamped tf;
  tf.header = header(stamp, 0, parent);
  tf.child_frame_id = child;
  const geometry_msgs::Pose pose = poseMessage(T_parent_child);
  tf.transform.translation.x = pose.position.x;
  tf.transform.translation.y = pose.position.y;
  tf.transform.translation.z = pose.position.z;
  tf.transform.rotation = pose.orientation;
  return tf;
}

}  // namespace bimloc::sim
