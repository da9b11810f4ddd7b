// What a particle needs of the plan, precomputed per room: which room a point is in (a grid
// of candidate rooms, so the lookup does not grow with the building) and the room's wall
// faces as landmarks in the minimal form of the paper's plane error.
#pragma once

#include "cell_scale.hpp"
#include "face_index.hpp"

#include <bimloc/bim/building.hpp>

#include <Eigen/Core>
#include <array>
#include <cmath>
#include <memory>
#include <vector>

namespace bimloc::pf::detail {

class RoomIndex {
 public:
  // With use_rooms = false every room sees every wall face of the storey (the ablation). With
  // neighbours, a room also sees the faces of the rooms it shares a wall with: through a door
  // the lidar sees into them, and those planes are evidence too, not clutter.
  // index_faces = false keeps the brute-force list without the room factor (the tests' oracle).
  RoomIndex(const bim::Storey& storey, bool use_rooms, bool neighbours = true, double cell_m = 0.5, bool index_faces = true);

  // The room whose footprint holds (x, y); in a doorway (inside a wall's thickness, in no
  // footprint) the room within doorway_m of it; -1 outside every room.
  int roomAt(double x, double y) const;
  // False where roomAt(x, y) cannot be `room`: beyond its footprint's bounding box grown by the
  // doorway reach. A test of four numbers, for callers that only want one room.
  bool mayBeIn(int room, double x, double y) const {
    const auto& box = boxes_[static_cast<std::size_t>(room)];
    return x >= box[0] && y >= box[1] && x <= box[2] && y <= box[3];
  }
  // The faces a particle in `room` matches against. Without the room factor: every face of
  // the storey, which a caller should reach through faceIndex() instead.
  const std::vector<Landmark>& landmarks(int room) const {
    if (!use_rooms_) return all_faces_ ? all_faces_->faces() : landmarks_[0];
    return landmarks_[static_cast<std::size_t>(room)];
  }
  // The same faces of one axis (the paper's classes: an x plane matches only x faces), in the
  // same order: what a match of an observation goes through, without the other half. Without
  // the room factor, every face of either axis (the caller checks the axis).
  const std::vector<Landmark>& landmarks(int room, bim::WallAxis axis) const {
    if (!use_rooms_) return landmarks(room);
    return by_axis_[static_cast<std::size_t>(room)][axis == bim::WallAxis::X ? 0 : 1];
  }
  // The same faces of one side of the axis (wallSide, landmark.hpp), in the same order; side -1:
  // both sides, landmarks(room, axis). Built only with index_faces (the tests' brute force keeps
  // the axis lists).
  const std::vector<Landmark>& landmarks(int room, bim::WallAxis axis, int side) const {
    if (!use_rooms_ || side < 0 || by_side_.empty()) return landmarks(room, axis);
    return by_side_[static_cast<std::size_t>(room)][static_cast<std::size_t>(side)];
  }
  // faceIndex() with only one side's faces in its cells (its faces() the same list, the same
  // positions); null where faceIndex() is.
  const FaceIndex* sideIndex(int side) const { return side_faces_[static_cast<std::size_t>(side)].get(); }
  // Every face of the storey by where it is, so that a match costs the faces near the
  // observation, not the building: without the room factor, and for a pose outside every
  // room. Null only when built with index_faces = false (the tests' brute-force oracle).
  const FaceIndex* faceIndex() const { return all_faces_.get(); }
  // The same faces in 1 m cells, the cells of the index before matching moved to 2 m ones.
  // Which faces a little beyond the radius a query returns, and in which order, depend on the
  // cells; they decide which pairs of faces the global pose hypotheses try, and which of two
  // faces that fit an observation exactly alike (collinear pieces of a wall) a match keeps.
  // Through this index both stay what they were. Null exactly when faceIndex() is.
  const FaceIndex* fineIndex() const { return fine_faces_.get(); }
  bool seesEveryFace() const { return !use_rooms_; }
  // How far behind a face with openings what fills them can stand: the deepest such wall's
  // thickness (measurement.cpp: a local search matches a plane in an opening as its filling).
  double fillingDepth() const { return filling_depth_m_; }
  std::size_t roomCount() const { return rooms_.size(); }
  const bim::Room& room(int index) const { return *rooms_[static_cast<std::size_t>(index)]; }

 private:
  bool use_rooms_ = true;
  std::vector<const bim::Room*> rooms_;
  std::vector<std::vector<Landmark>> landmarks_;
  std::vector<std::array<std::vector<Landmark>, 2>> by_axis_;  // landmarks_ split by axis (x, y), in order
  std::vector<std::array<std::vector<Landmark>, 4>> by_side_;  // landmarks_ split by side (wallSide), in order
  std::shared_ptr<const FaceIndex> all_faces_;  // shared: copies of the index share it
  std::array<std::shared_ptr<const FaceIndex>, 4> side_faces_;  // all_faces_'s by side (wallSide)
  std::shared_ptr<const FaceIndex> fine_faces_;
  double filling_depth_m_ = 0;
  Eigen::Vector2d origin_ = Eigen::Vector2d::Zero();
  double cell_m_ = 0.5;
  CellScale per_cell_{0.5};  // x / cell_m_, the same bits
  int nx_ = 0, ny_ = 0;
  std::vector<std::vector<int>> cells_;  // candidate rooms per cell
  // Per cell, what containing() answers for every point of it, where that does not depend on the
  // point: the room (or -1, none) where no footprint edge comes near the cell;
  // bim::kCellUnsure (the polygons asked) otherwise (bim::wholeCellAnswers).
  std::vector<int> sure_;
  std::vector<std::array<double, 4>> boxes_;  // per room: x and y least, x and y most, grown (mayBeIn)
  int containing(double x, double y) const;
};

}  // namespace bimloc::pf::detail
