// The plan's walls as a 2D slice: every wall face cut at one height above its base, its
// openings at that height left as gaps (doors; windows start higher). What a planar lidar at
// that height would hit, and what a walking body must keep clear of.
#pragma once

#include <bimloc/bim/building.hpp>

#include <Eigen/Core>
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <vector>

namespace bimloc::guide::detail {

struct Segment2 {
  Eigen::Vector2d a = Eigen::Vector2d::Zero(), b = Eigen::Vector2d::Zero();
  int wall = -1;  // the storey's wall it is a piece of
};

// Items (rooms, segments) by the cells of a grid that their boxes cover: those whose box may
// overlap a query box are the members of the cells it covers (floor is monotone: a box holding
// a point covers the point's cell). At most 1024 cells a side: a site's coordinates can span
// kilometres. A box (x, y least, x, y most) with a non-finite or reversed corner is in no cell.
class BoxCells {
 public:
  BoxCells() = default;
  BoxCells(const std::vector<Eigen::Vector4d>& boxes, double cell_m);
  bool empty() const { return nx_ == 0; }
  // Calls visit(item) for each member of each cell over [x0, x1] x [y0, y1] (an item may come
  // once per cell it covers); nothing when the query misses the grid.
  template <class Visit>
  void forEach(double x0, double y0, double x1, double y1, Visit&& visit) const {
    if (nx_ == 0 || !(x1 >= origin_.x() && y1 >= origin_.y() && x0 <= origin_.x() + nx_ * cell_m_ && y0 <= origin_.y() + ny_ * cell_m_))
      return;
    for (long iy = cell(y0, origin_.y(), ny_); iy <= cell(y1, origin_.y(), ny_); ++iy)
      for (long ix = cell(x0, origin_.x(), nx_); ix <= cell(x1, origin_.x(), nx_); ++ix) {
        const std::size_t c = static_cast<std::size_t>(iy * nx_ + ix);
        for (std::size_t i = starts_[c]; i < starts_[c + 1]; ++i) visit(members_[i]);
      }
  }
  static bool usable(const Eigen::Vector4d& b) { return b.allFinite() && b.x() <= b.z() && b.y() <= b.w(); }

 private:
  long cell(double v, double o, long n) const { return std::clamp(static_cast<long>(std::floor((v - o) / cell_m_)), 0L, n - 1); }
  double cell_m_ = 2.0;
  Eigen::Vector2d origin_ = Eigen::Vector2d::Zero();
  long nx_ = 0, ny_ = 0;
  std::vector<std::size_t> starts_, members_;  // cell k's items: members_[starts_[k] .. starts_[k + 1])
};

// Whether a point is in any room of the storey: storey.roomAt(p) != nullptr, the same answer,
// with each room's outline tested only where its bounding box holds the point (a goal's
// reachability asks it for every trial goal of every place, and a storey of 100 rooms made
// each answer 100 outline tests), and only the boxes over the point's cell of a grid looked
// at (100 box tests an answer were still the building's size, not what the robot sees).
class RoomBoxes {
 public:
  explicit RoomBoxes(const bim::Storey& storey);
  bool inAnyRoom(const Eigen::Vector2d& p) const;

 private:
  bool inRoom(std::size_t r, const Eigen::Vector2d& p) const;
  const bim::Storey* storey_ = nullptr;
  std::vector<Eigen::Vector4d> boxes_;  // per room: x and y least, x and y most, grown by 1e-6 m
  // The finite boxes by cells; rooms with a non-finite outline (a box over everything) are
  // tested wherever the point is.
  BoxCells cells_;
  std::vector<std::size_t> everywhere_;
};

// The solid pieces of every face of the storey at `height_m` above the face's base.
std::vector<Segment2> sliceWalls(const bim::Storey& storey, double height_m);

// The segments with a point within `radius_m` of `centre`.
std::vector<Segment2> segmentsNear(const std::vector<Segment2>& segments, const Eigen::Vector2d& centre, double radius_m);

// segmentsNear over one set of segments, the same list in the same order, through a grid of
// their boxes: the cost is what lies near, not the storey's every wall.
class SegmentGrid {
 public:
  SegmentGrid() = default;  // no segments
  explicit SegmentGrid(const std::vector<Segment2>& segments, double cell_m = 2.0);  // kept by reference
  std::vector<Segment2> near(const Eigen::Vector2d& centre, double radius_m) const;

 private:
  const std::vector<Segment2>* segments_ = nullptr;
  BoxCells cells_;                             // the segments' boxes
  std::vector<std::size_t> everywhere_;        // segments with a non-finite end: tested always
  mutable std::vector<std::uint32_t> seen_;    // per segment: the query that took it last
  mutable std::uint32_t stamp_ = 0;
};

// Distance from the ray's origin to the first segment along it, or max_m; with `wall`, that
// segment's wall (-1: none within max_m).
double castRay(const std::vector<Segment2>& segments, const Eigen::Vector2d& origin, const Eigen::Vector2d& direction,
               double max_m, int* wall = nullptr);

// castRay's test of one segment: whether the ray meets it nearer than `best` (then `best` is
// that distance).
bool rayMeets(const Segment2& s, const Eigen::Vector2d& origin, const Eigen::Vector2d& direction, double& best);

// The distance from p to segment s.
double distanceTo(const Segment2& s, const Eigen::Vector2d& p);

}  // namespace bimloc::guide::detail
