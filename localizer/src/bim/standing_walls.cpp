#include <bimloc/bim/standing_walls.hpp>

#include "extraction.hpp"

#include <algorithm>

namespace bimloc::bim {

std::size_t StandingWallsReport::total() const {
  std::size_t n = 0;
  for (const std::size_t a : added) n += a;
  return n;
}

namespace {

// How much of [lo, hi] the wall's body covers, in metres. A wall of unknown height (0) covers
// none: a map face where no wall stands would count against the true pose, a wall the map lacks
// is only clutter.
double bandOverlap(const Wall& wall, double lo, double hi) {
  if (!(wall.height_m > 0.0)) return 0.0;
  const double z0 = std::min(wall.start.z(), wall.end.z());
  return std::min(hi, z0 + wall.height_m) - std::max(lo, z0);
}

}  // namespace

Building withStandingWalls(const Building& building, const StandingWallsOptions& options,
                           StandingWallsReport* report) {
  Building out;
  out.file = building.file, out.schema = building.schema, out.stairs = building.stairs;
  out.warnings = building.warnings, out.times = building.times;
  out.storeys.reserve(building.storeys.size());
  std::vector<std::size_t> added(building.storeys.size(), 0);
  const ExtractOptions link_options;  // the extraction's adjacency rule, unchanged
  for (std::size_t s = 0; s < building.storeys.size(); ++s) {
    const Storey& storey = building.storeys[s];
    Storey copy;
    copy.id = storey.id, copy.name = storey.name, copy.elevation_m = storey.elevation_m;
    copy.elevation_source = storey.elevation_source;
    copy.rooms = storey.rooms, copy.walls = storey.walls;
    const double lo = storey.elevation_m + options.band_low_m, hi = storey.elevation_m + options.band_high_m;
    std::vector<Wall> standing;
    for (std::size_t t = 0; t < building.storeys.size(); ++t)
      if (t != s)
        for (const Wall& wall : building.storeys[t].walls)
          if (bandOverlap(wall, lo, hi) > options.min_overlap_m && !copy.findWall(wall.id)) standing.push_back(wall);
    // Link each room to the walls that bound it among the added ones, after its own: the room's
    // IfcRelSpaceBoundary (where it had one) dropped those as "a wall of another storey".
    for (Room& room : copy.rooms) {
      Room linked = room;
      detail::linkRoomByGeometry(linked, standing, link_options);
      room.walls.insert(room.walls.end(), linked.walls.begin(), linked.walls.end());
    }
    added[s] = standing.size();
    copy.walls.insert(copy.walls.end(), standing.begin(), standing.end());
    out.storeys.push_back(std::move(copy));
  }
  if (report) report->added = std::move(added);
  return out;
}

}  // namespace bimloc::bim
