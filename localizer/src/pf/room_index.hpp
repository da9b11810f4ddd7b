// What a particle needs of the plan, precomputed per room: which room a point is in (a grid
// of candidate rooms, so the lookup does not grow with the building) and the room's wall
// faces as landmarks in the minimal form of the paper's plane error.
#pragma once

#include <bimloc/bim/building.hpp>

#include <Eigen/Core>
#include <cmath>
#include <vector>

namespace bimloc::pf::detail {

struct Landmark {
  Eigen::Vector3d normal;  // out of the wall, into the room
  double d = 0;            // n·p + d = 0, map frame
  double azimuth = 0;      // atan2(n_y, n_x)
  double elevation = 0;    // asin(n_z)
  bim::WallAxis axis = bim::WallAxis::X;
  // The face's extent along the floor: an observed plane is this face only where its
  // points lie along it (a coplanar wall elsewhere in the building is another landmark).
  Eigen::Vector2d start = Eigen::Vector2d::Zero();
  Eigen::Vector2d direction = Eigen::Vector2d::UnitX();  // unit, start -> end
  double length_m = 0;
};

class RoomIndex {
 public:
  // With use_rooms = false every room sees every wall face of the storey (the ablation). With
  // neighbours, a room also sees the faces of the rooms it shares a wall with: through a door
  // the lidar sees into them, and those planes are evidence too, not clutter.
  RoomIndex(const bim::Storey& storey, bool use_rooms, bool neighbours = true, double cell_m = 0.5);

  // The room whose footprint holds (x, y); in a doorway (inside a wall's thickness, in no
  // footprint) the room within doorway_m of it; -1 outside every room.
  int roomAt(double x, double y) const;
  const std::vector<Landmark>& landmarks(int room) const { return landmarks_[static_cast<std::size_t>(room)]; }
  std::size_t roomCount() const { return rooms_.size(); }
  const bim::Room& room(int index) const { return *rooms_[static_cast<std::size_t>(index)]; }

 private:
  std::vector<const bim::Room*> rooms_;
  std::vector<std::vector<Landmark>> landmarks_;
  Eigen::Vector2d origin_ = Eigen::Vector2d::Zero();
  double cell_m_ = 0.5;
  int nx_ = 0, ny_ = 0;
  std::vector<std::vector<int>> cells_;  // candidate rooms per cell
  int containing(double x, double y) const;
};

Landmark makeLandmark(const bim::WallFace& face);
// Into [-pi, pi]. The filter's inner loops call it for every particle, observation and
// landmark: a branch instead of atan2(sin, cos).
inline double wrapAngle(double a) {
  if (a > M_PI) {
    a -= 2.0 * M_PI;
    if (a > M_PI) a = std::remainder(a, 2.0 * M_PI);
  } else if (a < -M_PI) {
    a += 2.0 * M_PI;
    if (a < -M_PI) a = std::remainder(a, 2.0 * M_PI);
  }
  return a;
}

}  // namespace bimloc::pf::detail
