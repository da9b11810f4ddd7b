// Small 2D polygon helpers used by the extraction and, later, the particle filter.
#pragma once

#include <Eigen/Core>
#include <vector>

namespace bimloc::bim {

using Polygon2 = std::vector<Eigen::Vector2d>;

double signedArea(const Polygon2& polygon);  // > 0 for counter-clockwise
Eigen::Vector2d areaCentroid(const Polygon2& polygon);
bool pointInPolygon(const Polygon2& polygon, const Eigen::Vector2d& p);
// The distance from p to the segment a-b (to a where a = b).
double distanceToSegment(const Eigen::Vector2d& p, const Eigen::Vector2d& a, const Eigen::Vector2d& b);
// The segments p-q and a-b cross at a point inside both (touching at an end, or collinear, is not crossing).
bool segmentsCross(const Eigen::Vector2d& p, const Eigen::Vector2d& q, const Eigen::Vector2d& a, const Eigen::Vector2d& b);
Polygon2 convexHull(std::vector<Eigen::Vector2d> points);  // counter-clockwise

// Point-in-room lookups on a grid of cells (cell (ix, iy) spans origin + cell_m [ix, ix + 1) x
// [iy, iy + 1), nx x ny of them, candidates[iy * nx + ix] the footprints, by index, that may
// hold its points, in the order the lookup tries them). Per cell: the first candidate holding
// the cell's centre (-1: none) where no edge of any footprint comes within 0.75 cells of the
// centre, which a cell's half diagonal (0.71) and a margin keep off the whole cell, so that the
// crossing test gives every point of the cell the centre's answer; kCellUnsure elsewhere (the
// lookup asks the polygons), and wherever a footprint with a coordinate that is not finite
// reaches. The edges are marked cell by cell over their boxes: a footprint of hundreds of
// corners over every cell (a comb-shaped corridor) costs its edges' cells, not cells x corners.
inline constexpr int kCellUnsure = -2;
std::vector<int> wholeCellAnswers(const std::vector<const Polygon2*>& footprints, const std::vector<std::vector<int>>& candidates,
                                  const Eigen::Vector2d& origin, double cell_m, int nx, int ny);

// Minimum-area enclosing rectangle of a convex polygon (rotating calipers).
struct Rectangle2 {
  Eigen::Vector2d centre = Eigen::Vector2d::Zero();
  Eigen::Vector2d axis = Eigen::Vector2d::UnitX();  // unit direction of the long side
  double length = 0.0;                              // along axis
  double width = 0.0;                               // across axis
};
Rectangle2 minAreaRectangle(const Polygon2& hull);

// Intersection over union of two simple polygons (either orientation): the areas exactly,
// the intersection by sampling on a grid of resolution_m (error about perimeter x resolution / 2).
double polygonIoU(const Polygon2& a, const Polygon2& b, double resolution_m = 0.01);

// Drops repeated and collinear vertices (within tol_m) and makes the polygon counter-clockwise.
Polygon2 simplifyPolygon(const Polygon2& polygon, double tol_m = 1e-4);

}  // namespace bimloc::bim
