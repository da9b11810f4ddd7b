#include "wall_slice.hpp"

#include <bimloc/bim/geometry2d.hpp>

#include <algorithm>
#include <cmath>

namespace bimloc::guide::detail {
namespace {

double cross2(const Eigen::Vector2d& u, const Eigen::Vector2d& v) { return u.x() * v.y() - u.y() * v.x(); }

}  // namespace

RoomBoxes::RoomBoxes(const bim::Storey& storey) : storey_(&storey) {
  for (const auto& room : storey.rooms) {
    // pointInPolygon counts a crossing only beyond the point within the outline's extent: a
    // point outside the box is outside the room (1e-6 m covers the rounding of the crossing's x).
    Eigen::Vector4d box(1e300, 1e300, -1e300, -1e300);
    bool finite = true;
    for (const auto& q : room.footprint)
      finite &= q.allFinite(), box.head<2>() = box.head<2>().cwiseMin(q), box.tail<2>() = box.tail<2>().cwiseMax(q);
    boxes_.push_back(finite ? Eigen::Vector4d(box.x() - 1e-6, box.y() - 1e-6, box.z() + 1e-6, box.w() + 1e-6)
                            : Eigen::Vector4d(-1e300, -1e300, 1e300, 1e300));
  }
}

bool RoomBoxes::inAnyRoom(const Eigen::Vector2d& p) const {
  for (std::size_t r = 0; r < boxes_.size(); ++r) {
    const Eigen::Vector4d& b = boxes_[r];
    if (p.x() >= b.x() && p.y() >= b.y() && p.x() <= b.z() && p.y() <= b.w() && bim::pointInPolygon(storey_->rooms[r].footprint, p))
      return true;
  }
  return false;
}

std::vector<Segment2> sliceWalls(const bim::Storey& storey, double height_m) {
  std::vector<Segment2> out;
  for (std::size_t w = 0; w < storey.walls.size(); ++w)
    for (const auto& face : storey.walls[w].faces) {
      const double length = face.length_m();
      if (!(length > 1e-3)) continue;
      const double z = face.start.z() + height_m;
      // The gaps at that height along the face, merged, then the solid stretches between them.
      std::vector<std::pair<double, double>> gaps;
      for (const auto& o : face.openings)
        if (o.z_min_m <= z && o.z_max_m >= z) gaps.emplace_back(std::max(0.0, o.along_min_m), std::min(length, o.along_max_m));
      std::sort(gaps.begin(), gaps.end());
      const Eigen::Vector2d a = face.start.head<2>(), dir = (face.end - face.start).head<2>() / length;
      double from = 0;
      const auto solid = [&](double lo, double hi) {
        if (hi - lo > 1e-3) out.push_back({a + lo * dir, a + hi * dir, static_cast<int>(w)});
      };
      for (const auto& [lo, hi] : gaps) {
        if (hi <= from) continue;
        solid(from, lo);
        from = std::max(from, hi);
      }
      solid(from, length);
    }
  return out;
}

std::vector<Segment2> segmentsNear(const std::vector<Segment2>& segments, const Eigen::Vector2d& centre, double radius_m) {
  std::vector<Segment2> out;
  for (const auto& s : segments)
    if (distanceTo(s, centre) <= radius_m) out.push_back(s);
  return out;
}

double castRay(const std::vector<Segment2>& segments, const Eigen::Vector2d& origin, const Eigen::Vector2d& direction,
               double max_m, int* wall) {
  double best = max_m;
  if (wall) *wall = -1;
  for (const auto& s : segments)
    if (rayMeets(s, origin, direction, best) && wall) *wall = s.wall;
  return best;
}

bool rayMeets(const Segment2& s, const Eigen::Vector2d& origin, const Eigen::Vector2d& direction, double& best) {
  const Eigen::Vector2d e = s.b - s.a;
  const double denom = cross2(direction, e);
  if (std::abs(denom) < 1e-12) return false;  // parallel: a grazing ray hits the neighbouring face
  const Eigen::Vector2d w = s.a - origin;
  const double t = cross2(w, e) / denom, u = cross2(w, direction) / denom;
  if (!(t > 0 && t < best && u >= 0 && u <= 1)) return false;
  best = t;
  return true;
}

double distanceTo(const Segment2& s, const Eigen::Vector2d& p) {
  const Eigen::Vector2d e = s.b - s.a;
  const double l2 = e.squaredNorm();
  const double u = l2 > 0 ? std::clamp((p - s.a).dot(e) / l2, 0.0, 1.0) : 0.0;
  return (s.a + u * e - p).norm();
}

}  // namespace bimloc::guide::detail
