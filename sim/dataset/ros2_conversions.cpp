#include "sim/dataset/ros2_conversions.hpp"

#include "sim/dataset/tum_writer.hpp"

namespace bimloc::sim {

ros2::Pose ros2Pose(const Eigen::Isometry3d& T) {
  ros2::Pose p;
  p.position = {T.translation().x(), T.translation().y(), T.translation().z()};
  const Eigen::Quaterniond q = canonicalRotation(T);
  p.orientation = {q.x(), q.y(), q.z(), q.w()};
  return p;
}

ros2::TransformStamped ros2Transform(std::uint64_t stamp_ns, const std::string& parent, const std::string& child,
                                     const Eigen::Isometry3d& T_parent_child) {
  ros2::TransformStamped t;
  t.header.stamp = ros2::Time::fromNanoseconds(static_cast<std::int64_t>(stamp_ns));
  t.header.frame_id = parent;
  t.child_frame_id = child;
  const ros2::Pose p = ros2Pose(T_parent_child);
  t.transform.translation = p.position;
  t.transform.rotation = p.orientation;
  return t;
}

}  // namespace bimloc::sim
