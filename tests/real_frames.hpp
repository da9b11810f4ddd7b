// Real lidar frames of one room (../shared/realdata/nebula/, SOURCES.md there): the wall planes
// the project's extractor finds in each, and the planar pose of one sensor relative to another
// from those planes alone. See docs/realdata_room.md for what was measured with them.
#pragma once

#include <bimloc/planes/plane_extraction.hpp>

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <string>
#include <utility>
#include <vector>

namespace bimloc::test {

// The five sensors' folders under nebula/, the VLP-16 (the reference) first.
inline const std::vector<std::string> kNebulaSensors = {"vlp16", "40p", "64", "xt32", "qt64"};

// The one .pcd of nebula/SENSOR/, or "" when ../shared/realdata is absent.
std::string nebulaPcd(const std::string& sensor);

// The points that stand up: those of 10 cm columns (sensor frame, x-y) whose returns span at
// least 0.3 m in height, and at least 1.5 m from the sensor. A dense lidar's near-horizontal
// rings lie in thin horizontal slabs that hold more voxels than a cluttered room's walls
// (docs/realdata_room.md): sequential RANSAC takes them first and their bands eat the walls.
// Floors, table tops and the rings' slabs over them have no height; walls, shelves and doors do.
std::vector<Eigen::Vector3f> standingPoints(const std::vector<Eigen::Vector3f>& points);

// The extractor's settings for these frames: 5000 RANSAC iterations instead of 500 (a wall is a
// few percent of the cloud: three points on it in 500 draws is a coin toss), 20 voxels minimum
// (a wall seen between shelves), up to 60 planes.
planes::PlaneExtractionConfig realFrameConfig();
// The same on a whole frame: realFrameConfig() with the extractor's own standing stage
// (standing_height_m 0.3) in place of standingPoints().
planes::PlaneExtractionConfig wholeFrameConfig();

// extractPlanes(standingPoints(points), realFrameConfig()).walls: the walls the room was measured
// by (docs/realdata_room.md), with the selection of the first measurement kept, so that the pose
// each frame's walls give stays the one the plan was made from.

std::vector<planes::ObservedPlane> realFrameWalls(const std::vector<Eigen::Vector3f>& points);

// The pose (x, y, yaw) of sensor B in sensor A's frame that lays most of B's walls on A's:
// every yaw a pair of walls proposes, every translation two non-parallel pairs propose, scored
// by how many of B's walls then lie within 3 degrees and 0.10 m of one of A's (each of A's used
// once). A room's walls alone leave a rectangle's two readings (and, with few walls, other
// pairings) tied: among the hypotheses with the most matched walls, the one under which B's
// standing points land on A's (10 cm cells, x-y) decides: the clutter is not symmetric. Where
// B's matched walls run in one direction only, the other axis is searched the same way. Then
// least squares on the matched walls. Walls are compared in the plane (x-y normal, d).
struct WallAlignment {
  Eigen::Vector3d pose = Eigen::Vector3d::Zero();   // B in A: x, y (m), yaw (rad)
  std::vector<std::pair<int, int>> matches;         // (A's wall, B's wall)
  int directions = 0;            // distinct wall directions (mod 180 deg) among the matches
  double worst_angle_deg = 0;    // after refinement, over the matches
  double worst_offset_m = 0;
  // The best hypothesis with the yaw turned by 180 degrees (the rectangle's other reading):
  // its matched walls. Fewer than `matches`: the clutter told the two apart.
  int turned_matches = 0;
  // The share of B's standing points on A's (see above), at the pose and at the best
  // hypothesis turned by 180 degrees.
  double overlap = 0, turned_overlap = 0;
};
WallAlignment alignWalls(const std::vector<planes::ObservedPlane>& a, const std::vector<Eigen::Vector3f>& a_standing,
                         const std::vector<planes::ObservedPlane>& b, const std::vector<Eigen::Vector3f>& b_standing);

struct RealFrame {
  std::string sensor;
  std::vector<Eigen::Vector3f> points;    // the whole frame, as the PCD has it
  std::vector<Eigen::Vector3f> standing;  // standingPoints(points)
  std::vector<planes::ObservedPlane> walls;  // realFrameWalls(points)
  // extractPlanes(points, wholeFrameConfig()).walls: the whole frame, the extractor's own
  // standing stage choosing where walls are searched.
  std::vector<planes::ObservedPlane> whole_walls;
  WallAlignment in_vlp;  // the sensor's pose in the VLP-16's frame (zero for the VLP-16)
};
// The five frames in kNebulaSensors' order, read, extracted and aligned once per process; null
// when ../shared/realdata is absent.
const std::vector<RealFrame>* nebulaFrames();

// The sensor's pose (x, y, yaw) in the plan of worlds/nebula_room.ifc, from its walls alone:
// the VLP-16 from its west wall and shelf front (docs/realdata_room.md, section 3), the others
// through their alignment on it. `shelf_from_south_m`: the shelving's front from the room's south
// wall, as measured (6.56 m, docs/realdata_room.md section 3: the VLP-16 does not see the south
// wall).
Eigen::Vector3d poseInRoom(const RealFrame& frame, const RealFrame& vlp16, double shelf_from_south_m);

}  // namespace bimloc::test
