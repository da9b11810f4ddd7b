// The likelihood field of Probabilistic Robotics section 6.4 (ROS amcl map_update_cspace): for
// every cell, the distance to the nearest occupied cell, capped at likelihood_max_dist.
#pragma once

#include "peers/amcl/grid.hpp"

#include <vector>

namespace bimloc::peers::amcl {

class LikelihoodField {
 public:
  LikelihoodField(const Grid& grid, double max_dist_m);
  // Distance [m] between the centres of cell (i, j) and of its nearest occupied cell, at most
  // max_dist_m (also with no occupied cell at all, and off the map, as ROS amcl's max_occ_dist).
  double distance(int i, int j) const { return grid_->contains(i, j) ? distance_m_[grid_->index(i, j)] : max_dist_m_; }
  const std::vector<float>& distances() const { return distance_m_; }
  double maxDistance() const { return max_dist_m_; }
  const Grid& grid() const { return *grid_; }

 private:
  const Grid* grid_;
  double max_dist_m_;
  std::vector<float> distance_m_;  // row-major, as the grid
};

}  // namespace bimloc::peers::amcl
