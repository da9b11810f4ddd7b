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
