// The Situational Graph's state (paper, "S-Graph based Localization"), plain data:
//   tracking layer         keyframes (the window being optimized, and the history),
//   metric-semantic layer  wall nodes: the plan's walls and new planes,
//   topological layer      room nodes tied to the walls around them.
// The Ceres problem is built from it for each optimization (window_solver.cpp).
#pragma once

#include "marginal_prior.hpp"
#include "wall_geometry.hpp"

#include <bimloc/bim/geometry2d.hpp>
#include <bimloc/sgraph/sgraph_tracker.hpp>

#include <Eigen/Geometry>
#include <array>
#include <deque>
#include <optional>
#include <string>
#include <vector>

namespace bimloc::sgraph::detail {

using bimloc::between;  // geometry/planar_pose.hpp
using bimloc::compose;
using bimloc::tiltOf;

// One keyframe-plane factor: an observed plane and the face it was associated with.
struct PlaneMeasurement {
  int node = -1;
  int face = 0;
  Eigen::Vector3d minimal = Eigen::Vector3d::Zero();  // observed (azimuth, elevation, d), lidar frame
  Eigen::Matrix3d sqrt_information = Eigen::Matrix3d::Identity();
  Eigen::Vector2d centroid_map = Eigen::Vector2d::Zero();  // where its points were (map, at the keyframe)
  double extent_m = 0;
  int observation = -1;  // index of the observed wall in its scan
};

// A keyframe of the robot-tracking layer. Its estimated state is planar (x, y, yaw): a legged
// base walks on a floor, and vertical walls say nothing about its height and little about its
// roll and pitch (the elevation of a wall's normal moves by the tilt alone, and the IMU-aided
// odometry already knows the gravity direction), so those come from odometry and the graph
// estimates the three degrees of freedom the walls do constrain.
struct Keyframe {
  int id = -1;
  double stamp_s = 0;
  Eigen::Isometry3d T_odom_base = Eigen::Isometry3d::Identity();
  Eigen::Vector3d odom = Eigen::Vector3d::Zero();  // planar odometry pose
  std::array<double, 3> pose{};                    // x, y, yaw in the map: the Ceres block
  Eigen::Vector3d predicted = Eigen::Vector3d::Zero();  // from odometry, before optimizing
  Eigen::Matrix3d tilt = Eigen::Matrix3d::Identity();
  double z_map = 0;
  Eigen::Matrix3d A = Eigen::Matrix3d::Identity();  // tilt * R_base_lidar (plane_factor.hpp)
  Eigen::Vector3d b = Eigen::Vector3d::Zero();      // tilt * t_base_lidar
  bool odometry_jump = false;  // the odometry jumped since the previous keyframe: weak link
  std::vector<PlaneMeasurement> planes;
  int plan_walls = 0;

  Eigen::Vector3d planar() const { return {pose[0], pose[1], pose[2]}; }
  Eigen::Isometry3d T_map_base() const;
};

struct WallNode {
  enum class Kind { Plan, New };
  Kind kind = Kind::Plan;
  int wall = -1;    // Plan: index into the storey's walls
  int new_id = -1;  // New: its public id
  bool active = true;  // false: unusable plan wall, or a new plane merged into a plan wall
  int faces = 2;       // New: 1
  std::array<FaceGeometry, 2> face;
  std::array<Eigen::Vector2d, 2> start{}, end{};  // extent of each face along the floor
  std::array<std::vector<bim::FaceOpening>, 2> openings;  // Plan: the face's holes (along from start, z)
  std::array<bool, 2> buried{};  // Plan: the face lies inside another wall's body (bim/buried_faces.hpp)
  std::array<double, 3> params{};                 // s, alpha, tau: the Ceres block
  int observations = 0;
  int last_keyframe = -1;  // the newest keyframe that saw it
  std::vector<int> rooms;  // room nodes it is part of

  Eigen::Vector2d normal(int k) const;  // current estimate
  double d(int k) const;
  bim::WallAxis axis(int k) const;
  // Position of a map point along face k, from its start (its extent is [0, length]).
  double along(int k, const Eigen::Vector2d& p) const;
  double length(int k) const { return (end[k] - start[k]).norm(); }
};

struct FaceRef {
  int node = -1;
  int face = 0;
};

struct RoomData {
  int room = -1;  // index into the storey's rooms
  std::string name;
  bool corridor = false;
  std::vector<FaceRef> pairs;          // 4 (two opposite pairs) or 2 (one pair)
  std::vector<FaceRef> faces;          // every face looking into the room
  bim::Polygon2 footprint;
  Eigen::Vector2d plan_centre = Eigen::Vector2d::Zero();  // where the factor is zero on the plan
  std::array<double, 2> centre{};                         // the Ceres block
};

// An observed wall that matched nothing yet: a new plane once seen in enough keyframes.
struct Candidate {
  WallNode plane;  // a one-faced node at its first sighting
  std::vector<std::pair<int, PlaneMeasurement>> sightings;  // keyframe id, measurement
  int last_keyframe = -1;
};

struct Graph {
  std::deque<Keyframe> window;  // oldest first; references stay valid as it slides
  std::vector<KeyframeInfo> history;  // every keyframe, frozen when it leaves the window
  std::vector<WallNode> nodes;  // the storey's walls first (index = wall index), then new planes
  std::vector<RoomData> rooms;
  std::vector<Candidate> candidates;
  // The prior on window.front() and the walls the marginalized keyframes saw (or, before any
  // was marginalized, the initial pose).
  MarginalPrior prior;
  int next_keyframe_id = 0;
  int next_new_plane_id = 0;
  // The base's map z at the first keyframe, standing on the storey's floor (the hand-over, or
  // the arrival from the stairs): a keyframe far from it is on a flight, where the lidar does
  // not see the storey as the plan's floor view has it (loss_monitor.cpp).
  std::optional<double> floor_base_z;
};

}  // namespace bimloc::sgraph::detail
