// A wall face as a landmark in the minimal form of the paper's plane error (azimuth,
// elevation, d), with its extent along the floor.
#pragma once

#include <bimloc/geometry/planar_pose.hpp>

#include <bimloc/bim/building.hpp>

#include <Eigen/Core>
#include <algorithm>
#include <cmath>
#include <limits>
#include <vector>

namespace bimloc::pf::detail {

struct Landmark {
  // What a match reads of every face it tries (the normal, d, the angles, the heights) comes
  // first: 64 bytes, one or two cache lines of the 160 (measurement.cpp's loop over a room's
  // faces waited on the heights' line). The order of the members changes no value.
  Eigen::Vector3d normal = Eigen::Vector3d::UnitX();  // out of the wall, into the room
  double d = 0;            // n·p + d = 0, map frame
  double azimuth = 0;      // atan2(n_y, n_x)
  double elevation = 0;    // asin(n_z)
  // The face's vertical extent in the map (the wall's body, base to top): an observed plane
  // is this face only where its points lie at heights the wall has. A wall hung above the
  // rooms' ceilings (a stair well's enclosure on the storey above, a bulkhead) is in the plan
  // but never in a scan taken from the floor; matched, it pulls a pose onto furniture or a
  // counter front that happens to stand a few decimetres off it (the Duplex: 0.4 m in y).
  double z_bottom = -std::numeric_limits<double>::infinity();
  double z_top = std::numeric_limits<double>::infinity();
  bim::WallAxis axis = bim::WallAxis::X;
  // The face's extent along the floor: an observed plane is this face only where its
  // points lie along it (a coplanar wall elsewhere in the building is another landmark).
  Eigen::Vector2d start = Eigen::Vector2d::Zero();
  Eigen::Vector2d direction = Eigen::Vector2d::UnitX();  // unit, start -> end
  double length_m = 0;
  // The face's wall line along it, from its start (wall_lines.hpp): an observed plane's points
  // must all lie along it, not only its centroid along the face. Unbounded: not known.
  double line_lo_m = -std::numeric_limits<double>::infinity();
  double line_hi_m = std::numeric_limits<double>::infinity();
  // The face's holes (windows, doors, recesses; along from start, map z): used only where the
  // association is local (the converged pose's refinement, as the S-Graph), see measurement.hpp.
  const std::vector<bim::FaceOpening>* openings = nullptr;  // the storey's, which outlives it
  // How deep behind the face what fills its openings can stand: the wall's thickness. A window's
  // pane and frame, a shut door's leaf, stand within the wall's body (0: not known).
  double depth_m = 0;
  int id = -1;  // which face of the storey: 2 * wall index + face index
};

// How far outside a face's vertical extent an observed plane's points may lie and still be
// that face: the plane's vertical span is estimated from its support's centroid and height
// extent (not its exact ends), the base's height from odometry. 0.5 m covers both; walls that
// are seen are floor to ceiling, and a wall 0.5 m clear of the scan's points is not what it saw.
constexpr double kVerticalMarginM = 0.5;

// Which side of its axis a horizontal normal (nx, ny) faces: 0 +x, 1 -x, 2 +y, 3 -y (the axis
// as Landmark::axis, |nx| >= |ny| for x, then the sign of that component); -1 when its horizontal
// part is under 0.5 long (a plane tilted over 60 deg), too short to tell, or not finite. Two normals of one axis
// and opposite sides are at least 90 deg apart (n . m <= 0: |n_y m_y| <= |n_x m_x| = -n_x m_x),
// so where the gate's angle is narrower, a plane of one side can never match a face of the
// other (measurement.cpp): the match leaves those faces out.
inline int wallSide(double nx, double ny) {
  const double ax = std::abs(nx), ay = std::abs(ny);
  if (!std::isfinite(ax) || !std::isfinite(ay) || std::max(ax, ay) < 0.5) return -1;
  return ax >= ay ? (nx >= 0.0 ? 0 : 1) : (ny >= 0.0 ? 2 : 3);
}
// Whether a face with this normal belongs to `side`'s faces: its own side, or either side of its
// axis where its side cannot be told.
inline bool onSide(const Landmark& l, int side) {
  const int own = wallSide(l.normal.x(), l.normal.y());
  return own >= 0 ? own == side : (side < 2) == (l.axis == bim::WallAxis::X);
}

// height_m: the wall's height from the face's base (start.z); 0 or less: unknown, unbounded.
Landmark makeLandmark(const bim::WallFace& face, int id = -1, double height_m = 0.0);
using bimloc::wrapAngle;  // geometry/planar_pose.hpp

}  // namespace bimloc::pf::detail
