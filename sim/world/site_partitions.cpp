#include "sim/world/site_partitions.hpp"

#include "sim/common/seeded_random.hpp"

#include <bimloc/bim/geometry2d.hpp>

#include <algorithm>
#include <cmath>

namespace bimloc::sim {
namespace {

// Tries per partition: rooms too small for one are found out quickly and named in a warning.
constexpr int kDrawsPerPartition = 400;
// A door's leaf and swing: kept this much further from a partition than a wall is.
constexpr double kPartitionDoorSwing_m = 1.0;

}  // namespace

double segmentDistance(const Eigen::Vector2d& a0, const Eigen::Vector2d& a1, const Eigen::Vector2d& b0, const Eigen::Vector2d& b1) {
  if (bim::segmentsCross(a0, a1, b0, b1)) return 0.0;
  return std::min({bim::distanceToSegment(a0, b0, b1), bim::distanceToSegment(a1, b0, b1), bim::distanceToSegment(b0, a0, a1),
                   bim::distanceToSegment(b1, a0, a1)});
}

void placePartitions(const bim::Storey& storey, std::size_t storey_index, const SiteWalls& config,
                     const std::vector<Eigen::Affine3d>& wall_motions, const std::vector<Eigen::Vector2d>& door_centres,
                     std::uint64_t seed, ComposedStorey& out, SiteTruth& truth) {
  if (config.partitions_per_storey <= 0 || storey.rooms.empty()) return;
  // One stream per storey: a storey's partitions do not depend on the storeys below it.
  SeededRandom random(seed ^ (0x51ED2705ull * (storey_index + 1)), RandomStream::SitePartitions);
  const double keep = config.partition_clearance_m + 0.5 * config.partition_thickness_m;
  std::vector<std::pair<Eigen::Vector2d, Eigen::Vector2d>> placed;
  for (int k = 0; k < config.partitions_per_storey; ++k) {
    bool done = false;
    for (int draw = 0; draw < kDrawsPerPartition && !done; ++draw) {
      // Every draw takes the same numbers, so a rejection does not shift the ones after it.
      const double r_room = random.uniform(), r_x = random.uniform(), r_y = random.uniform(),
                   r_length = random.uniform(), r_turn = random.uniform();
      const bim::Room& room = storey.rooms[std::min(storey.rooms.size() - 1, std::size_t(r_room * storey.rooms.size()))];
      if (room.footprint.size() < 3) continue;
      Eigen::Vector2d lo = room.footprint.front(), hi = lo;
      for (const auto& q : room.footprint) lo = lo.cwiseMin(q), hi = hi.cwiseMax(q);
      const Eigen::Vector2d centre(lo.x() + r_x * (hi.x() - lo.x()), lo.y() + r_y * (hi.y() - lo.y()));
      const double length = config.partition_min_length_m + r_length * (config.partition_max_length_m - config.partition_min_length_m);
      // Along the room's main axis or across it, as boards are set up.
      Eigen::Vector2d axis = bim::minAreaRectangle(bim::convexHull(room.footprint)).axis;
      if (r_turn < 0.5) axis = Eigen::Vector2d(-axis.y(), axis.x());
      const Eigen::Vector2d a = centre - 0.5 * length * axis, b = centre + 0.5 * length * axis;
      if (!bim::pointInPolygon(room.footprint, a) || !bim::pointInPolygon(room.footprint, b)) continue;
      bool clear = true;
      for (std::size_t i = 0; clear && i < room.footprint.size(); ++i)
        clear = segmentDistance(a, b, room.footprint[i], room.footprint[(i + 1) % room.footprint.size()]) >= keep;
      for (std::size_t i = 0; clear && i < storey.walls.size(); ++i) {
        const bim::Wall& w = storey.walls[i];
        const Eigen::Vector2d s = (wall_motions[i] * Eigen::Vector3d(w.start.x(), w.start.y(), 0)).head<2>();
        const Eigen::Vector2d e = (wall_motions[i] * Eigen::Vector3d(w.end.x(), w.end.y(), 0)).head<2>();
        clear = segmentDistance(a, b, s, e) >= keep + 0.5 * w.thickness_m;
      }
      for (std::size_t i = 0; clear && i < door_centres.size(); ++i)
        clear = bim::distanceToSegment(door_centres[i], a, b) >= keep + kPartitionDoorSwing_m;
      for (std::size_t i = 0; clear && i < placed.size(); ++i)
        clear = segmentDistance(a, b, placed[i].first, placed[i].second) >= keep + 0.5 * config.partition_thickness_m;
      if (!clear) continue;
      const double z0 = room.floor_z;
      const double z1 = z0 + (room.height_m > 0 ? std::min(room.height_m, config.partition_height_m) : config.partition_height_m);
      const std::string id = "partition-" + std::to_string(storey_index) + "-" + std::to_string(k);
      appendBox(out, id, "Partition", a, b, config.partition_thickness_m, z0, z1);
      truth.partitions.push_back({storey_index, room.name, a, b, config.partition_thickness_m, z1 - z0});
      placed.emplace_back(a, b);
      done = true;
    }
    if (!done)
      truth.warnings.push_back("storey '" + storey.name + "': partition " + std::to_string(k + 1) + " of " +
                               std::to_string(config.partitions_per_storey) + " left out: no room has " +
                               std::to_string(config.partition_clearance_m) + " m clear around one");
  }
}

}  // namespace bimloc::sim
