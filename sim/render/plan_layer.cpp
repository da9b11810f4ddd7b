#include "sim/render/layers.hpp"

#include "sim/render/font.hpp"

#include <bimloc/bim/geometry2d.hpp>

#include <algorithm>
#include <limits>

namespace bimloc::sim::render {

namespace {

Points toPixels(const std::vector<Eigen::Vector2d>& world, const Layout& layout) {
  Points out;
  for (const auto& p : world) out.push_back(layout.toPixel(p));
  return out;
}

// The wall's footprint from its two faces: their four base corners, as a convex outline
// (the faces may run in opposite directions, and an approximated wall is still a box).
Points wallFootprint(const bim::Wall& wall, const Layout& layout) {
  std::vector<Eigen::Vector2d> corners;
  for (const auto& face : wall.faces) {
    corners.push_back(face.start.head<2>());
    corners.push_back(face.end.head<2>());
  }
  return toPixels(bim::convexHull(corners), layout);
}

double distanceToEdges(const bim::Polygon2& polygon, const Eigen::Vector2d& p) {
  double best = std::numeric_limits<double>::infinity();
  for (std::size_t i = 0; i < polygon.size(); ++i) {
    const Eigen::Vector2d a = polygon[i], ab = polygon[(i + 1) % polygon.size()] - a;
    const double t = std::clamp(ab.dot(p - a) / std::max(ab.squaredNorm(), 1e-12), 0.0, 1.0);
    best = std::min(best, (a + t * ab - p).norm());
  }
  return best;
}

// Where the name goes: the point of the room farthest from its outline (ties: nearest the
// centroid). The centroid itself can lie on a wall or outside an L-shaped corridor.
Eigen::Vector2d labelPoint(const bim::Room& room, const bim::Polygon2& footprint) {
  Eigen::Vector2d lo = footprint[0], hi = lo;
  for (const auto& p : footprint) lo = lo.cwiseMin(p), hi = hi.cwiseMax(p);
  Eigen::Vector2d best = room.centre;
  double best_score = bim::pointInPolygon(footprint, room.centre) ? distanceToEdges(footprint, room.centre) : -1e9;
  const int n = 24;
  for (int i = 0; i <= n; ++i)
    for (int j = 0; j <= n; ++j) {
      const Eigen::Vector2d p = lo + Eigen::Vector2d(i, j).cwiseProduct(hi - lo) / n;
      if (!bim::pointInPolygon(footprint, p)) continue;
      const double score = distanceToEdges(footprint, p) - 0.05 * (p - room.centre).norm();
      if (score > best_score + 1e-9) best = p, best_score = score;
    }
  return best;
}

void drawRoomLabel(const bim::Room& room, const Layout& layout) {
  const bim::Polygon2 footprint = bim::simplifyPolygon(room.footprint);
  if (footprint.size() < 3) return;
  Eigen::Vector2d lo = footprint[0], hi = lo;
  for (const auto& p : footprint) lo = lo.cwiseMin(p), hi = hi.cwiseMax(p);
  const Eigen::Vector2d at = labelPoint(room, footprint);
  // The room's width at the label is bounded by twice its distance to the outline, roughly.
  const double room_w_px = std::min(hi.x() - lo.x(), 2.4 * distanceToEdges(footprint, at)) * layout.px_per_m;
  const double room_h_px = std::min(hi.y() - lo.y(), 2.4 * distanceToEdges(footprint, at)) * layout.px_per_m;
  const std::string& name = room.name.empty() ? room.long_name : room.name;
  if (name.empty()) return;
  // Shrink the name to the room; the long name only where it fits beneath at full size.
  int scale = layout.text_scale;
  while (scale > 1 && textWidth(name, scale) > 0.8 * room_w_px) --scale;
  const bool second = !room.name.empty() && !room.long_name.empty() && room.long_name != room.name &&
                      textWidth(room.long_name, scale) <= 0.8 * room_w_px &&
                      2.5 * kLineHeight * scale <= room_h_px;
  const Eigen::Vector2d c = layout.toPixel(at);
  const double line = kLineHeight * scale;
  const double top = c.y() - (second ? line : 0.5 * line);
  drawText(c.x() - 0.5 * textWidth(name, scale), top, name, scale, hex(0x7d7d7d));
  if (second)
    drawText(c.x() - 0.5 * textWidth(room.long_name, scale), top + line, room.long_name, scale, hex(0xa8a8a8));
}

}  // namespace

void drawPlan(const bim::Storey& storey, const Layout& layout) {
  const double hairline = std::max(1.0, 0.5 * layout.text_scale);
  for (const auto& room : storey.rooms) {
    const bim::Polygon2 footprint = bim::simplifyPolygon(room.footprint);
    if (footprint.size() < 3) continue;
    const Points px = toPixels(footprint, layout);
    fillPolygon(px, hex(0xededed));
    strokePolyline(px, hairline, hex(0xcfcfcf), true);
  }
  for (const auto& wall : storey.walls) {
    const Points px = wallFootprint(wall, layout);
    if (px.size() < 3) continue;
    fillConvex(px, wallColour());
    // At least a hairline, so a thin partition stays visible in a large building.
    strokePolyline(px, hairline, wallColour(), true);
  }
}

void drawRoomLabels(const bim::Storey& storey, const Layout& layout) {
  for (const auto& room : storey.rooms) drawRoomLabel(room, layout);
}

}  // namespace bimloc::sim::render
