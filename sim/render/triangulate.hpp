// Triangles of a simple polygon, for filling room footprints that are not convex (L-shaped
// rooms): GL 1.x fills only convex polygons correctly.
#pragma once

#include <Eigen/Core>
#include <array>
#include <vector>

namespace bimloc::sim::render {

// Ear clipping; either winding; indices into `polygon`. A self-intersecting or degenerate
// polygon still gets a fan for what is left, so a bad footprint shows instead of vanishing.
std::vector<std::array<int, 3>> triangulate(const std::vector<Eigen::Vector2d>& polygon);

}  // namespace bimloc::sim::render
