// localized.bag of `bimloc localize` on a bag: every message of the input, plus what a
// localization node would have published (REP 105): /tf map -> odom, and /localization, a
// geometry_msgs/PoseWithCovarianceStamped of base_link in map (as amcl's /amcl_pose).
// rosbag stays inside localized_bag_writer.cpp.
#pragma once

#include <Eigen/Core>
#include <Eigen/Geometry>

#include <memory>
#include <string>

namespace bimloc::sim {

inline constexpr const char* kLocalizationTopic = "/localization";

class LocalizedBagWriter {
 public:
  // Creates `path` with a copy of every message of `input_bag`. Throws std::runtime_error
  // naming the file.
  LocalizedBagWriter(const std::string& path, const std::string& input_bag, std::string map_frame,
                     std::string odom_frame, std::string base_frame, std::string tf_topic);
  ~LocalizedBagWriter();
  LocalizedBagWriter(const LocalizedBagWriter&) = delete;
  LocalizedBagWriter& operator=(const LocalizedBagWriter&) = delete;

  // `covariance_xy_yaw`: of (x, y, yaw), placed in the message's 6x6 (x y z roll pitch yaw).
  void add(double stamp_s, const Eigen::Isometry3d& T_map_odom, const Eigen::Isometry3d& T_map_base,
           const Eigen::Matrix3d& covariance_xy_yaw);
  void close();

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace bimloc::sim
