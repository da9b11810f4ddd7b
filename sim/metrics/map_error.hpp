// The map RMSE of the paper's real-data table ("Point cloud RMSE"): the scans, placed with the
// estimated poses, against the plan's storey mesh. It needs no ground truth, so it scores
// recorded data as well as simulated runs: a wrong pose puts the walls' points off the walls.
#pragma once

#include "sim/metrics/mesh_distance.hpp"

#include <Eigen/Geometry>
#include <vector>

namespace bimloc::sim {

class MapError {
 public:
  // `stride`: every stride-th point of a scan is measured (a VLP-16 turn has ~30 000).
  explicit MapError(const bim::Storey& storey, int stride = 20) : mesh_(storey.mesh), stride_(stride < 1 ? 1 : stride) {}

  void add(const std::vector<Eigen::Vector3f>& points_lidar, const Eigen::Isometry3d& T_map_lidar);
  std::size_t points() const { return n_; }
  double rmse_m() const;  // 0 points: NaN

 private:
  MeshDistance mesh_;
  int stride_;
  std::size_t n_ = 0;
  double sum_sq_ = 0;
};

}  // namespace bimloc::sim
