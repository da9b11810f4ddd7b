// What AMCL publishes of its particles (ROS pf_cluster_stats and amcl_node): the mean of the
// heaviest cluster as the pose, the whole set's covariance as its uncertainty.
#pragma once

#include "peers/amcl/particles.hpp"

#include <Eigen/Core>

namespace bimloc::peers::amcl {

struct PoseStats {
  PlanarPose mean = PlanarPose::Zero();  // yaw: the weighted circular mean
  // x, y: the weighted covariance; yaw: the circular variance -2 ln |mean of (cos, sin)|
  // (ROS: "the correct formula for circular statistics"), no xy-yaw terms.
  Eigen::Matrix3d covariance = Eigen::Matrix3d::Zero();
  double weight = 0;
};

struct SetStats {
  PoseStats set;      // every particle
  PoseStats best;     // the cluster of the largest weight
  int clusters = 0;   // ROS pf_kdtree_cluster: connected occupied bins (26-neighbourhood)
};

SetStats clusterStats(const std::vector<Particle>& particles);

}  // namespace bimloc::peers::amcl
