// From a raster region's staircase outline to a room footprint: simplified, and its edges
// moved onto the wall faces they run along (the raster is only good to half a cell; the faces
// are exact, and the geometric room<->wall adjacency needs the footprint on the faces).
#pragma once

#include <bimloc/bim/building.hpp>
#include <bimloc/bim/geometry2d.hpp>
#include <bimloc/bim/room_inference.hpp>

#include <vector>

namespace bimloc::bim::detail {

// Douglas-Peucker on a closed polygon: no vertex of the result is farther than tolerance_m
// from the input's outline. Deterministic (starts from the lowest-leftmost vertex).
Polygon2 simplifyClosed(const Polygon2& polygon, double tolerance_m);

// Each edge that runs along a wall face looking into the room (parallel within the angle,
// within the distance, overlapping it) is moved onto that face; vertices become the
// intersections of consecutive edges' lines. Returns the input unchanged when the result
// would not be a simple polygon.
Polygon2 snapToFaces(const Polygon2& polygon, const std::vector<WallFace>& faces, const RoomInferenceConfig& config);

// No two non-adjacent edges cross or touch.
bool isSimplePolygon(const Polygon2& polygon);

}  // namespace bimloc::bim::detail
