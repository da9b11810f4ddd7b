// Topological layer: a room node tied to its walls (reference.md, "S-Graphs math": room from
// four planes, corridor from two). S-Graphs takes, for each pair of opposite walls, the
// midpoint of their closest points and sums the two midpoints; here the same condition is
// written as "the room centre is as far from one wall of a pair as from the other", which is
// that midpoint for parallel walls and does not depend on where the map's origin is:
//   r_pair = ((n_a · c + d_a) - (n_b · c + d_b)) / 2   (both normals look into the room).
// A room has two pairs (x and y walls), a corridor one: its centre along the corridor is
// left to the room node's prior (S-Graphs fixes it from the free space).
#pragma once

#include "wall_geometry.hpp"

#include <array>
#include <ceres/autodiff_cost_function.h>

namespace bimloc::sgraph::detail {

class RoomFactor {
 public:
  // faces[0], faces[1]: one opposite pair; faces[2], faces[3]: the other.
  RoomFactor(const std::array<FaceGeometry, 4>& faces, double sigma_m) : faces_(faces), inverse_sigma_(1.0 / sigma_m) {}

  template <typename T>
  bool operator()(const T* centre, const T* a, const T* b, const T* c, const T* d, T* residual) const {
    residual[0] = 0.5 * (faces_[0].distance(a, centre[0], centre[1]) - faces_[1].distance(b, centre[0], centre[1])) * inverse_sigma_;
    residual[1] = 0.5 * (faces_[2].distance(c, centre[0], centre[1]) - faces_[3].distance(d, centre[0], centre[1])) * inverse_sigma_;
    return true;
  }

  static ceres::CostFunction* create(const std::array<FaceGeometry, 4>& faces, double sigma_m) {
    return new ceres::AutoDiffCostFunction<RoomFactor, 2, 2, 3, 3, 3, 3>(new RoomFactor(faces, sigma_m));
  }

 private:
  std::array<FaceGeometry, 4> faces_;
  double inverse_sigma_;
};

class CorridorFactor {
 public:
  CorridorFactor(const std::array<FaceGeometry, 2>& faces, double sigma_m) : faces_(faces), inverse_sigma_(1.0 / sigma_m) {}

  template <typename T>
  bool operator()(const T* centre, const T* a, const T* b, T* residual) const {
    residual[0] = 0.5 * (faces_[0].distance(a, centre[0], centre[1]) - faces_[1].distance(b, centre[0], centre[1])) * inverse_sigma_;
    return true;
  }

  static ceres::CostFunction* create(const std::array<FaceGeometry, 2>& faces, double sigma_m) {
    return new ceres::AutoDiffCostFunction<CorridorFactor, 1, 2, 3, 3>(new CorridorFactor(faces, sigma_m));
  }

 private:
  std::array<FaceGeometry, 2> faces_;
  double inverse_sigma_;
};

}  // namespace bimloc::sgraph::detail
