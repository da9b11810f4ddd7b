// The wall line of each face: how far along it the plan has wall in that plane. A lidar sees a
// wall as one run of points (plane extraction bridges gaps under 0.5 m), and that run may
// cross from one face to the next one drawn in line with it (a wall modelled in pieces, a
// wall continuing past a junction), but never beyond where the plan's wall ends. Where an
// observed plane runs metres past the end of every face in line with the one it would match,
// that face is not what was seen: in a row of identical bays, a long wall seen along the row
// would otherwise be "explained" at the next bay by a partition that ends where the bay does.
#pragma once

#include <bimloc/bim/building.hpp>

#include <vector>

namespace bimloc::pf::detail {

// Faces in one plane: normals within kInLineRad of each other and planes within kInLineM
// (a wall drawn in pieces is in one plane to the millimetre; 0.1 m is the extraction's
// inlier band, 0.04 m, twice over with its refit, rounded up).
constexpr double kInLineM = 0.10;
constexpr double kInLineRad = 2.0 * M_PI / 180.0;
// Faces in line closer than this along the line are one wall line: a door drawn as a gap
// between two wall pieces (0.8-1.0 m), which a closed leaf or the frames may bridge in a scan.
constexpr double kLineGapM = 1.0;

// Along a face, from its start: the stretch [lo_m, hi_m] of its wall line (lo_m <= 0 and
// hi_m >= length).
struct LineSpan {
  double lo_m = 0;
  double hi_m = 0;
};

// Per face of the storey (index 2 * wall + face); a face marked in `ignored` (buried faces:
// no sensor sees them) neither joins a line nor gets one beyond its own extent.
std::vector<LineSpan> wallLines(const bim::Storey& storey, const std::vector<bool>& ignored);

}  // namespace bimloc::pf::detail
