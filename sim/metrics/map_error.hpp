// The map RMSE of the paper's real-data table ("Point cloud RMSE"): the scans, placed with the
// estimated poses, against the plan's storey mesh. It needs no ground truth, so it scores
// recorded data as well as simulated runs: a wrong pose puts the walls' points off the walls.
#pragma once

#include "sim/metrics/mesh_distance.hpp"

#include <bimloc/localizer.hpp>

#include <Eigen/Geometry>
#include <functional>
#include <optional>
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

// A run's map RMSE, the same for `bimloc run` and `bimloc localize`: one scan every
// `every_steps` localizer steps (a second at 10 Hz), once converged and while not lost, on the
// storey the localizer is on.
class MapErrorSampler {
 public:
  explicit MapErrorSampler(const bim::Building& building, int every_steps = 10) : building_(building), every_(every_steps) {}

  // After each step; `points_lidar` is called only for the scans measured.
  void step(const LocalizationResult& r, const Eigen::Isometry3d& T_base_lidar,
            const std::function<std::vector<Eigen::Vector3f>()>& points_lidar);
  std::optional<double> rmse_m() const;  // unset before the first point

 private:
  const bim::Building& building_;
  int every_;
  long steps_ = 0;
  std::optional<MapError> error_;
};

}  // namespace bimloc::sim
