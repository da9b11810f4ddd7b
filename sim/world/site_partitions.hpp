// Temporary partitions: free-standing boards placed at random in rooms. Each keeps
// SiteWalls::partition_clearance_m from every room outline edge, wall, door and other
// partition: a segment with that much free room all round cannot cut a room (or the robot's
// way through it) in two, so every tour the plan allows stays possible.
#pragma once

#include "sim/world/site_mesh.hpp"
#include "sim/world/site_truth.hpp"

namespace bimloc::sim {

// Places config.partitions_per_storey partitions on the storey (drawn from the seed), adds
// their boxes to `out` and their truth to `truth` (a partition with no room for it: a warning).
void placePartitions(const bim::Storey& storey, std::size_t storey_index, const SiteWalls& config,
                     const std::vector<Eigen::Affine3d>& wall_motions, const std::vector<Eigen::Vector2d>& door_centres,
                     std::uint64_t seed, ComposedStorey& out, SiteTruth& truth);

// Shortest distance between the segments a0-a1 and b0-b1 (XY).
double segmentDistance(const Eigen::Vector2d& a0, const Eigen::Vector2d& a1, const Eigen::Vector2d& b0, const Eigen::Vector2d& b1);

}  // namespace bimloc::sim
