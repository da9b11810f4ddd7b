// Clutter boxes in the rooms (SiteClutter): drawn from the seed, each against one edge of its
// room or free-standing, and `clearance_m` clear of everything else, so no passage closes.
#pragma once

#include "sim/world/site_mesh.hpp"
#include "sim/world/site_truth.hpp"

namespace bimloc::sim {

// Adds the storey's boxes to `out` and their truth to `truth` (after the partitions, which
// they keep clear of); rooms that cannot hold their share get a warning naming them.
void placeClutter(const bim::Storey& storey, std::size_t storey_index, const SiteClutter& config,
                  const std::vector<Eigen::Affine3d>& wall_motions, const std::vector<Eigen::Vector2d>& door_centres,
                  std::uint64_t seed, ComposedStorey& out, SiteTruth& truth);

}  // namespace bimloc::sim
