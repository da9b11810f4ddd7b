#include "room_index.hpp"

#include "bim/buried_faces.hpp"
#include "wall_lines.hpp"

#include <bimloc/bim/geometry2d.hpp>

#include <cmath>
#include <utility>

namespace bimloc::pf::detail {

Landmark makeLandmark(const bim::WallFace& face, int id, double height_m) {
  Landmark l;
  l.id = id;
  if (height_m > 0.0 && std::isfinite(face.start.z())) l.z_bottom = face.start.z(), l.z_top = face.start.z() + height_m;
  l.normal = face.plane.n.normalized();
  l.d = face.plane.d;
  l.openings = &face.openings;
  l.start = face.start.head<2>();
  const Eigen::Vector2d along = face.end.head<2>() - l.start;
  l.length_m = along.norm();
  if (l.length_m > 1e-9) l.direction = along / l.length_m;
  l.azimuth = std::atan2(l.normal.y(), l.normal.x());
  l.elevation = std::asin(std::clamp(l.normal.z(), -1.0, 1.0));
  l.axis = std::abs(l.normal.x()) >= std::abs(l.normal.y()) ? bim::WallAxis::X : bim::WallAxis::Y;
  return l;
}

namespace {

// A doorway belongs to no room's footprint: the robot crossing it is walking from one room
// into the next, and either room's walls are what it sees. Walls are at most 0.6 m thick.
constexpr double kDoorwayM = 0.3;

// A face as a landmark, with its wall line.
Landmark landmarkOf(const bim::Storey& storey, std::size_t w, int f, const std::vector<LineSpan>& lines) {
  Landmark l = makeLandmark(storey.walls[w].faces[f], static_cast<int>(2 * w) + f, storey.walls[w].height_m);
  const LineSpan& line = lines[2 * w + static_cast<std::size_t>(f)];
  l.line_lo_m = line.lo_m, l.line_hi_m = line.hi_m;
  l.depth_m = std::max(0.0, storey.walls[w].thickness_m);
  return l;
}

// The faces of a room's walls that look into it (both, where the side is unknown).
std::vector<Landmark> facesOf(const bim::Storey& storey, const bim::Room& room, const std::vector<bool>& buried,
                              const std::vector<LineSpan>& lines) {
  std::vector<Landmark> faces;
  for (const auto& rw : room.walls) {
    const bim::Wall* wall = storey.findWall(rw.wall_id);
    if (!wall) continue;
    const int w = static_cast<int>(wall - storey.walls.data());
    for (int f = 0; f < 2; ++f)
      if ((rw.face < 0 || rw.face == f) && !buried[static_cast<std::size_t>(2 * w + f)])
        faces.push_back(landmarkOf(storey, static_cast<std::size_t>(w), f, lines));
  }
  return faces;
}

bool shareAWall(const bim::Room& a, const bim::Room& b) {
  for (const auto& wa : a.walls)
    for (const auto& wb : b.walls)
      if (wa.wall_id == wb.wall_id) return true;
  return false;
}

}  // namespace

RoomIndex::RoomIndex(const bim::Storey& storey, bool use_rooms, bool neighbours, double cell_m, bool index_faces)
    : use_rooms_(use_rooms), cell_m_(cell_m), per_cell_(cell_m) {
  // Faces inside another wall's body are no landmarks (buried_faces.hpp); ids stay 2 w + f.
  const std::vector<bool> buried = bim::buriedFaces(storey);
  const std::vector<LineSpan> lines = wallLines(storey, buried);
  std::vector<Landmark> every_face;
  for (std::size_t w = 0; w < storey.walls.size(); ++w)
    for (int f = 0; f < 2; ++f)
      if (!buried[2 * w + static_cast<std::size_t>(f)]) every_face.push_back(landmarkOf(storey, w, f, lines));
  for (const auto& l : every_face)
    if (l.openings && !l.openings->empty()) filling_depth_m_ = std::max(filling_depth_m_, l.depth_m);
  Eigen::Vector2d lo(1e300, 1e300), hi(-1e300, -1e300);
  // 2 m cells: a match radius is 3-7 m, and with 1 m cells walking the cells cost more than
  // matching the faces in them.
  if (index_faces) {
    all_faces_ = std::make_shared<const FaceIndex>(every_face, 2.0);
    fine_faces_ = std::make_shared<const FaceIndex>(every_face, 1.0);
    for (int side = 0; side < 4; ++side) {
      std::vector<bool> keep;
      for (const Landmark& l : every_face) keep.push_back(onSide(l, side));
      side_faces_[static_cast<std::size_t>(side)] = std::make_shared<const FaceIndex>(every_face, 2.0, keep);
    }
  }
  if (!use_rooms && !index_faces) landmarks_.push_back(every_face);  // one list for every room
  for (const auto& room : storey.rooms) {
    rooms_.push_back(&room);
    if (!use_rooms) {
      for (const auto& p : room.footprint) lo = lo.cwiseMin(p), hi = hi.cwiseMax(p);
      continue;
    }
    std::vector<Landmark> faces = facesOf(storey, room, buried, lines);
    if (use_rooms && neighbours)
      for (const auto& other : storey.rooms)
        if (&other != &room && shareAWall(room, other)) {
          const auto more = facesOf(storey, other, buried, lines);
          faces.insert(faces.end(), more.begin(), more.end());
        }
    std::array<std::vector<Landmark>, 2> split;
    for (const Landmark& l : faces) split[l.axis == bim::WallAxis::X ? 0 : 1].push_back(l);
    by_axis_.push_back(std::move(split));
    if (index_faces) {
      std::array<std::vector<Landmark>, 4> sides;
      for (const Landmark& l : faces)
        for (int side = 0; side < 4; ++side)
          if (onSide(l, side)) sides[static_cast<std::size_t>(side)].push_back(l);
      by_side_.push_back(std::move(sides));
    }
    landmarks_.push_back(std::move(faces));
    for (const auto& p : room.footprint) lo = lo.cwiseMin(p), hi = hi.cwiseMax(p);
  }
  // A point of a footprint lies in its bounding box (pointInPolygon counts no crossing beyond
  // it; 1e-6 m covers the rounding of x + s); roomAt looks up to kDoorwayM beside the point.
  for (const bim::Room* room : rooms_) {
    Eigen::Vector2d a(1e300, 1e300), b(-1e300, -1e300);
    bool finite = true;
    for (const auto& p : room->footprint) finite &= p.allFinite(), a = a.cwiseMin(p), b = b.cwiseMax(p);
    const double grow = kDoorwayM + 1e-6;
    boxes_.push_back(finite ? std::array<double, 4>{a.x() - grow, a.y() - grow, b.x() + grow, b.y() + grow}
                            : std::array<double, 4>{-1e300, -1e300, 1e300, 1e300});
  }
  if (rooms_.empty()) return;
  origin_ = lo;
  nx_ = static_cast<int>(std::ceil((hi.x() - lo.x()) / cell_m_)) + 1;
  ny_ = static_cast<int>(std::ceil((hi.y() - lo.y()) / cell_m_)) + 1;
  cells_.assign(static_cast<std::size_t>(nx_ * ny_), {});
  for (int r = 0; r < static_cast<int>(rooms_.size()); ++r) {
    Eigen::Vector2d a = rooms_[static_cast<std::size_t>(r)]->footprint.front(), b = a;
    for (const auto& p : rooms_[static_cast<std::size_t>(r)]->footprint) a = a.cwiseMin(p), b = b.cwiseMax(p);
    const int x0 = static_cast<int>((a.x() - origin_.x()) / cell_m_), x1 = static_cast<int>((b.x() - origin_.x()) / cell_m_);
    const int y0 = static_cast<int>((a.y() - origin_.y()) / cell_m_), y1 = static_cast<int>((b.y() - origin_.y()) / cell_m_);
    for (int ix = x0; ix <= x1; ++ix)
      for (int iy = y0; iy <= y1; ++iy) cells_[static_cast<std::size_t>(iy * nx_ + ix)].push_back(r);
  }
  // A cell no footprint edge comes near is inside or outside each footprint as a whole
  // (geometry2d.hpp; the crossing test's rounding is 1e-14 m at a storey's coordinates).
  std::vector<const bim::Polygon2*> footprints;
  for (const bim::Room* room : rooms_) footprints.push_back(&room->footprint);
  sure_ = bim::wholeCellAnswers(footprints, cells_, origin_, cell_m_, nx_, ny_);
}

int RoomIndex::roomAt(double x, double y) const {
  if (const int r = containing(x, y); r >= 0) return r;
  for (const double s : {0.5 * kDoorwayM, kDoorwayM})
    for (const auto& [dx, dy] : {std::pair{1.0, 0.0}, {-1.0, 0.0}, {0.0, 1.0}, {0.0, -1.0}})
      if (const int r = containing(x + s * dx, y + s * dy); r >= 0) return r;
  return -1;
}

int RoomIndex::containing(double x, double y) const {
  const int ix = static_cast<int>(std::floor(per_cell_(x - origin_.x())));
  const int iy = static_cast<int>(std::floor(per_cell_(y - origin_.y())));
  if (ix < 0 || iy < 0 || ix >= nx_ || iy >= ny_) return -1;
  if (const int sure = sure_[static_cast<std::size_t>(iy * nx_ + ix)]; sure != bim::kCellUnsure) return sure;
  for (const int r : cells_[static_cast<std::size_t>(iy * nx_ + ix)])
    if (bim::pointInPolygon(rooms_[static_cast<std::size_t>(r)]->footprint, {x, y})) return r;
  return -1;
}

}  // namespace bimloc::pf::detail
