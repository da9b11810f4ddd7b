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
  for (std::size_t r = 0; r < boxes_.size(); ++r)
    if (boxes_[r].x() == -1e300) everywhere_.push_back(r);
  // The grid over the finite boxes (an empty room's outline gives a reversed box: in no cell).
  std::vector<Eigen::Vector4d> finite(boxes_);
  for (std::size_t r : everywhere_) finite[r] = Eigen::Vector4d::Constant(std::nan(""));
  cells_ = BoxCells(finite, 2.0);
}

BoxCells::BoxCells(const std::vector<Eigen::Vector4d>& boxes, double cell_m) : cell_m_(cell_m) {
  Eigen::Vector2d lo(1e300, 1e300), hi(-1e300, -1e300);
  for (const auto& b : boxes)
    if (usable(b)) lo = lo.cwiseMin(b.head<2>()), hi = hi.cwiseMax(b.tail<2>());
  if (!(lo.x() <= hi.x() && lo.y() <= hi.y())) return;
  origin_ = lo;
  cell_m_ = std::max({cell_m, (hi.x() - lo.x()) / 1024.0, (hi.y() - lo.y()) / 1024.0});
  nx_ = static_cast<long>(std::floor((hi.x() - lo.x()) / cell_m_)) + 1, ny_ = static_cast<long>(std::floor((hi.y() - lo.y()) / cell_m_)) + 1;
  std::vector<std::vector<std::size_t>> cells(static_cast<std::size_t>(nx_ * ny_));
  for (std::size_t k = 0; k < boxes.size(); ++k) {
    const Eigen::Vector4d& b = boxes[k];
    if (!usable(b)) continue;
    for (long iy = cell(b.y(), lo.y(), ny_); iy <= cell(b.w(), lo.y(), ny_); ++iy)
      for (long ix = cell(b.x(), lo.x(), nx_); ix <= cell(b.z(), lo.x(), nx_); ++ix) cells[static_cast<std::size_t>(iy * nx_ + ix)].push_back(k);
  }
  starts_.assign(cells.size() + 1, 0);
  for (std::size_t k = 0; k < cells.size(); ++k) {
    starts_[k + 1] = starts_[k] + cells[k].size();
    members_.insert(members_.end(), cells[k].begin(), cells[k].end());
  }
}

bool RoomBoxes::inRoom(std::size_t r, const Eigen::Vector2d& p) const {
  const Eigen::Vector4d& b = boxes_[r];
  return p.x() >= b.x() && p.y() >= b.y() && p.x() <= b.z() && p.y() <= b.w() && bim::pointInPolygon(storey_->rooms[r].footprint, p);
}

bool RoomBoxes::inAnyRoom(const Eigen::Vector2d& p) const {
  for (const std::size_t r : everywhere_)
    if (inRoom(r, p)) return true;
  if (!p.allFinite()) return false;
  bool in = false;
  cells_.forEach(p.x(), p.y(), p.x(), p.y(), [&](std::size_t r) { in = in || inRoom(r, p); });
  return in;
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

SegmentGrid::SegmentGrid(const std::vector<Segment2>& segments, double cell_m) : segments_(&segments) {
  seen_.assign(segments.size(), 0);
  std::vector<Eigen::Vector4d> boxes;
  for (std::size_t k = 0; k < segments.size(); ++k) {
    const Segment2& s = segments[k];
    const Eigen::Vector2d a = s.a.cwiseMin(s.b), b = s.a.cwiseMax(s.b);
    boxes.emplace_back(a.x(), a.y(), b.x(), b.y());
    if (!BoxCells::usable(boxes.back())) everywhere_.push_back(k);
  }
  cells_ = BoxCells(boxes, cell_m);
}

std::vector<Segment2> SegmentGrid::near(const Eigen::Vector2d& centre, double radius_m) const {
  if (!segments_) return {};
  // Not a finite disc (or no grid): the plain scan.
  if (cells_.empty() || !centre.allFinite() || !std::isfinite(radius_m)) return segmentsNear(*segments_, centre, radius_m);
  std::vector<std::size_t> picked(everywhere_);
  if (++stamp_ == 0) std::fill(seen_.begin(), seen_.end(), 0u), stamp_ = 1;
  // A segment with a point within the radius has that point in the disc's box.
  cells_.forEach(centre.x() - radius_m, centre.y() - radius_m, centre.x() + radius_m, centre.y() + radius_m, [&](std::size_t k) {
    if (seen_[k] != stamp_) seen_[k] = stamp_, picked.push_back(k);
  });
  std::sort(picked.begin(), picked.end());  // the segments' own order
  std::vector<Segment2> out;
  for (const std::size_t k : picked)
    if (distanceTo((*segments_)[k], centre) <= radius_m) out.push_back((*segments_)[k]);
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
