// Rooms as a scenario names them: by name (R101), GlobalId, or long name (Office) when that is
// unique on the storey. Shared by the scenario checks and the planner so both agree.
#pragma once

#include <bimloc/bim/building.hpp>

#include <Eigen/Core>
#include <string>
#include <vector>

namespace bimloc::sim {

// The room, or nullptr with `problem` set: unknown (listing the storey's rooms) or ambiguous.
const bim::Room* lookUpRoom(const bim::Storey& storey, const std::string& name_or_id, std::string* problem);

// "R101 (Office), R102 (Office), C100 (Corridor)", or "none" for a storey without rooms.
std::string roomList(const bim::Storey& storey);

// The room whose footprint contains p, or nullptr.
const bim::Room* roomAt(const bim::Storey& storey, const Eigen::Vector2d& p);

// roomAt through a grid of candidate rooms per cell: the planner asks it for every step of
// every edge it tries, and a scan over every room made path planning grow with the building.
// The same answer as roomAt (the first room in the storey's order whose footprint holds p):
// each cell lists, in that order, every room whose padded bounding box touches it.
class RoomGrid {
 public:
  explicit RoomGrid(const bim::Storey& storey);
  const bim::Room* at(const Eigen::Vector2d& p) const;

 private:
  const bim::Storey* storey_;
  Eigen::Vector2d origin_ = Eigen::Vector2d::Zero();
  double cell_m_ = 1.0;
  int nx_ = 0, ny_ = 0;
  std::vector<std::vector<int>> cells_;
  // Per cell, its answer for every point in it where no footprint edge comes near it (the room's
  // index, -1 for none), else bim::kCellUnsure (bim::wholeCellAnswers): a comb-shaped
  // corridor's footprint of hundreds of corners (a 600-room office floor) lies over every
  // cell, and the planner asks at every step.
  std::vector<int> sure_;
  int cellX(double x) const;
  int cellY(double y) const;
};

}  // namespace bimloc::sim
