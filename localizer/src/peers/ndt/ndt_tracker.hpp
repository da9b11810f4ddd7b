// Scan-to-map registration with PCL's NormalDistributionsTransform (Magnusson 2009), as
// hdl_localization tracks, and its fitness. PCL stays in the .cpp.
#pragma once

#include "peers/ndt/map_cloud.hpp"

#include <bimloc/peers/ndt_config.hpp>

#include <Eigen/Geometry>
#include <memory>

namespace bimloc::peers {

struct NdtAlignment {
  Eigen::Isometry3d T_map_lidar = Eigen::Isometry3d::Identity();
  double fitness_m2 = 0;        // mean squared nearest-map distance of the matched points
  double inlier_fraction = 0;   // share of the points within fitness_max_distance_m of the map
  int iterations = 0;
  bool good = false;            // fitness and inliers within the config's limits
};

class NdtTracker {
 public:
  NdtTracker(const Cloud3& map, const NdtConfig& config);
  ~NdtTracker();
  bool ready() const;  // the map has points
  // scan: lidar frame, already downsampled; guess: where the lidar is in the map.
  NdtAlignment align(const Cloud3& scan, const Eigen::Isometry3d& guess_map_lidar) const;
  // The fitness of the scan at a pose, without registering (the same measure as align's).
  NdtAlignment fitness(const Cloud3& scan, const Eigen::Isometry3d& T_map_lidar) const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace bimloc::peers
