// The walls a robot standing on each storey senses: the storey's own, and the walls filed under
// another storey that stand in its wall band. A plan files each element under one storey, but
// split levels put walls of one storey beside the floor of another (Jesse.1's façade is filed
// under the half level above the basement it encloses; the basement's walls rise through that
// half level). The lidar sees what stands there, whichever storey the file names.
#pragma once

#include <bimloc/bim/building.hpp>

#include <cstddef>
#include <vector>

namespace bimloc::bim {

struct StandingWallsOptions {
  // The band above a storey's floor where the plan's wall faces are what the lidar sees: above
  // most furniture tops, below door heads (the oracle's band, docs/oracle.md). A wall of another
  // storey whose body overlaps it by more than min_overlap_m stands in the storey (one of
  // unknown height, 0, does not: a map face where no wall stands counts against the true pose).
  double band_low_m = 0.3;
  double band_high_m = 1.8;
  double min_overlap_m = 0.1;  // the topology's vertical overlap (topology.cpp)
};

struct StandingWallsReport {
  std::vector<std::size_t> added;  // per storey: walls of other storeys added to it
  std::size_t total() const;
};

// A copy of `building` whose every storey also holds the walls of other storeys that stand in
// its band (same ids, names and geometry; their z range is the wall's own), each linked to the
// storey's rooms whose footprint its face lies on (topology by geometry). Storey meshes and mesh
// parts are not copied (the localizer does not cast rays). A plan of one storey, or one whose
// storeys do not overlap, comes back with the same walls.
Building withStandingWalls(const Building& building, const StandingWallsOptions& options = {},
                           StandingWallsReport* report = nullptr);

}  // namespace bimloc::bim
