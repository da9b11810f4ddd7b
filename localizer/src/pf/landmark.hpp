// A wall face as a landmark in the minimal form of the paper's plane error (azimuth,
// elevation, d), with its extent along the floor.
#pragma once

#include <bimloc/geometry/planar_pose.hpp>

#include <bimloc/bim/building.hpp>

#include <Eigen/Core>
#include <cmath>

namespace bimloc::pf::detail {

struct Landmark {
  Eigen::Vector3d normal = Eigen::Vector3d::UnitX();  // out of the wall, into the room
  double d = 0;            // n·p + d = 0, map frame
  double azimuth = 0;      // atan2(n_y, n_x)
  double elevation = 0;    // asin(n_z)
  bim::WallAxis axis = bim::WallAxis::X;
  // The face's extent along the floor: an observed plane is this face only where its
  // points lie along it (a coplanar wall elsewhere in the building is another landmark).
  Eigen::Vector2d start = Eigen::Vector2d::Zero();
  Eigen::Vector2d direction = Eigen::Vector2d::UnitX();  // unit, start -> end
  double length_m = 0;
  int id = -1;  // which face of the storey: 2 * wall index + face index
};

Landmark makeLandmark(const bim::WallFace& face, int id = -1);
using bimloc::wrapAngle;  // geometry/planar_pose.hpp

}  // namespace bimloc::pf::detail
