// Where the body fits on a storey, asked of Bullet: sweeps of the body's sphere at body height.
// Path search runs on a grid whose edges (between neighbouring cell centres) are such sweeps,
// evaluated only when A* reaches them and then cached; the A* path is then pulled taut into a
// few straight segments, again checked by sweeps.
#pragma once

#include "sim/base/chunked_cells.hpp"
#include "sim/base/room_lookup.hpp"

#include <bimloc/bim/geometry2d.hpp>

#include <Eigen/Core>
#include <cstdint>
#include <optional>
#include <vector>

namespace bimloc::sim {

class World;

// Height of the body's centre when it stands at p: the floor under p (or the storey's
// elevation where no floor is found) plus body_height_m. Storeys are flat: the planner keeps it.
double bodyCentreZ(const World& world, std::size_t storey, const Eigen::Vector2d& p, double body_height_m);

class FreeSpace {
 public:
  // Planned paths keep this much more than the body radius from the building: the check of the
  // final segments (exact radius) then never fails on a path the planner made.
  static constexpr double kMargin_m = 0.03;
  // Small enough that a 0.9 m door (0.8 m between its 5 cm jambs) has a cell line through it
  // for a 0.3 m body plus the margin.
  static constexpr double kCell_m = 0.05;
  // Corners closer than this are merged into one where the straight lines allow it.
  static constexpr double kMergeCorners_m = 0.5;

  FreeSpace(const World& world, std::size_t storey, double radius_m, double body_z_m);

  double bodyZ() const { return body_z_; }
  double radius() const { return radius_; }
  // Can the body, grown by margin_m, move from a to b? `contact`: the first point touched.
  bool segmentClear(const Eigen::Vector2d& a, const Eigen::Vector2d& b, double margin_m,
                    Eigen::Vector3d* contact = nullptr) const;
  // Does the body, grown by margin_m, fit at p?
  bool spotFree(const Eigen::Vector2d& p, double margin_m, Eigen::Vector3d* contact = nullptr) const;
  // p itself when the body fits there with the margin, else the nearest grid point where it
  // does (inside `area` when given, within max_distance_m).
  std::optional<Eigen::Vector2d> freeSpotNear(const Eigen::Vector2d& p, const bim::Polygon2* area,
                                              double max_distance_m) const;
  // A path from a to b as its corners (a first, b last), clear with the margin except where a
  // or b themselves are closer; empty when b cannot be reached.
  std::vector<Eigen::Vector2d> path(const Eigen::Vector2d& a, const Eigen::Vector2d& b);
  // A path from a into `area` (a room's outline): to b when b can be reached, else to the
  // reachable grid point inside `area` nearest b; empty when no point of `area` can be reached.
  // A room's free spot nearest its centre may be a pocket walled in by furniture (a living
  // room's centre between sofa and table): the room is still reachable, that spot is not.
  std::vector<Eigen::Vector2d> pathInto(const Eigen::Vector2d& a, const Eigen::Vector2d& b, const bim::Polygon2& area);
  std::size_t sweepCount() const { return sweeps_; }

 private:
  struct Grid {
    Eigen::Vector2d origin = Eigen::Vector2d::Zero();  // centre of cell (0, 0)
    int nx = 0, ny = 0;
    ChunkedCells<std::uint8_t> edges;  // 2 bits per direction E, NE, N, NW: 0 unknown, 1 clear, 2 blocked
  };
  void makeGrid(const Eigen::Vector2d& a, const Eigen::Vector2d& b);
  Eigen::Vector2d centre(int cell) const;
  int cellNear(const Eigen::Vector2d& p) const;  // -1 outside the grid
  bool edgeClear(int cell, int direction);       // direction 0..7, E then counter-clockwise
  bool indoors(const Eigen::Vector2d& p) const;
  // segmentClear, and indoors all along when paths must stay in the building.
  bool passable(const Eigen::Vector2d& a, const Eigen::Vector2d& b, double margin_m) const;
  // Cells from `from` to `to`; empty when `to` cannot be reached, and then, if `reached` is
  // given, the cells that can be (the whole component of `from`: A* closed them all; 1 where
  // reached).
  std::vector<int> aStar(int from, int to, ChunkedCells<std::uint8_t>* reached = nullptr);
  int joinGrid(const Eigen::Vector2d& p) const;  // grid point reached from p by a clear segment, -1 if none
  void useRule(const Eigen::Vector2d& a, const Eigen::Vector2d& b);  // indoors_only_ for a path a -> b
  std::vector<Eigen::Vector2d> corners(const Eigen::Vector2d& a, const std::vector<int>& cells,
                                       const Eigen::Vector2d& b) const;  // a, the cells, b pulled taut
  std::vector<Eigen::Vector2d> pullTaut(const std::vector<Eigen::Vector2d>& points) const;
  std::vector<Eigen::Vector2d> straighten(std::vector<Eigen::Vector2d> corners) const;

  const World& world_;
  std::size_t storey_;
  RoomGrid rooms_;  // indoors() asks it for every step of every edge A* tries
  double radius_, body_z_;
  Grid grid_;
  mutable std::size_t sweeps_ = 0;
  bool indoors_only_ = false;
  static constexpr double kDoorway_m = 0.35;  // a doorway is within a wall's thickness of a room
};

}  // namespace bimloc::sim
