// Tracking the robot in the plan with a Situational Graph (paper, section "S-Graph based
// Localization"): the plan gives the top two layers (walls as planes, rooms linked to their
// walls); once the particle filter has converged, keyframes of the robot join them as the
// tracking layer, observed wall planes are associated with the plan's walls (or become new
// planes), and a sliding window of the graph is optimized (Ceres, kept out of this header).
//
// Frames (REP 105): map = the plan's frame W, odom, base_link, and the lidar. Walls in the
// map are n·p + d = 0 with the normal out of the wall; observed planes are in the lidar frame
// with the normal towards the sensor (planes/plane_extraction.hpp), so both sides agree.
#pragma once

#include <bimloc/bim/building.hpp>
#include <bimloc/planes/plane_extraction.hpp>

#include <Eigen/Geometry>
#include <memory>
#include <optional>
#include <string>
#include <vector>

namespace bimloc::sgraph {

struct SGraphConfig {
  // Keyframes: a scan becomes one after this much motion (odometry) since the last keyframe.
  // S-Graphs uses 2 m / 2 rad for mapping; a tracker wants them denser.
  double keyframe_spacing_m = 1.0;
  double keyframe_spacing_deg = 20.0;
  // Sliding window: the keyframes optimized together; older ones are marginalized into a
  // prior on the oldest kept keyframe and the walls they saw.
  int window_keyframes = 10;

  // Keyframe-plane factor (reference: S-Graphs' keyframe-plane edge in (azimuth, elevation,
  // d)): the plane fit's own covariance plus these floors, for what the fit does not know
  // (walls not quite flat, the plane's part of the lidar motion).
  double plane_sigma_azimuth_deg = 1.0;
  double plane_sigma_elevation_deg = 1.0;
  double plane_sigma_d_m = 0.02;

  // Plane association (paper, "Plane Association"): class x / y by the dominant normal
  // component, then the Mahalanobis distance in (azimuth, elevation, d), with the prediction's
  // uncertainty (odometry since the last optimized keyframe) added to the observation's.
  double association_sigma_azimuth_deg = 3.0;
  double association_sigma_d_m = 0.08;
  double association_gate_mahalanobis2 = 11.34;  // chi-square, 3 DoF, 99 %
  double segment_margin_m = 0.5;  // the observed plane's centroid must lie along the face, to within this
  // An observed plane whose support (centroid -+ half its extents) lies inside one of a plan
  // face's openings, grown by this, is not that face (a window's glass, a door leaf): the
  // extents come from 0.1 m voxels, and the pose while tracking is good to a few centimetres.
  double opening_margin_m = 0.15;
  int new_plane_min_sightings = 3;  // an unmatched wall seen in this many keyframes becomes a new plane
  int candidate_max_age_keyframes = 10;  // ... and is forgotten when unseen for this many
  // Room association (paper, "Room Association"): a room seen from its walls matches a plan
  // room whose centre is within this (rooms do not overlap: up to about a room's half width).
  double room_match_distance_m = 1.0;
  // ... and a new plane among its walls is merged into the room's plan wall on that side when
  // it lies within this of it (farther: another wall, e.g. a partition the plan does not have).
  double merge_max_offset_m = 0.5;

  // Odometry factor between consecutive keyframes: sigma = floor + rate * motion, per axis
  // (legged odometry drifts 0.1-2 % of distance: reference.md, "Legged base and odometry").
  double odometry_sigma_xy_per_m = 0.02;
  double odometry_sigma_xy_floor_m = 0.005;
  double odometry_sigma_yaw_per_rad = 0.02;
  double odometry_sigma_yaw_per_m_deg = 0.3;  // heading drift per metre walked
  double odometry_sigma_yaw_floor_deg = 0.1;
  // An odometry increment beyond these between two scans is a jump: warned, and the link to
  // the next keyframe gets these as its sigmas (the map decides).
  double odometry_jump_m = 1.0;
  double odometry_jump_deg = 45.0;

  // The initial pose (the particle filter's, at convergence: within 0.3 m / 5 deg).
  double initial_sigma_xy_m = 0.3;
  double initial_sigma_yaw_deg = 5.0;

  // As-built tolerance of the plan: each wall may sit off its plan position by about this
  // (shift along its normal, rotation about its centre), so a wall built off the plan is
  // estimated instead of dragging the robot.
  double wall_prior_sigma_m = 0.05;
  double wall_prior_sigma_deg = 1.0;  // at most; a long wall's is wall_prior_sigma_m over half its length
  double wall_thickness_sigma_m = 0.02;  // thickness vs the plan (seen only from both sides)
  // A room node sits where the mid-planes of its opposite walls cross (room factor); its plan
  // centre is only a loose prior: the walls already carry the plan's tolerance, and a room
  // with one wall 0.4 m off has its centre 0.2 m off (a tight prior would pull the walls back).
  double room_prior_sigma_m = 0.5;
  double room_factor_sigma_m = 0.02;
  // What marginalized keyframes said is one Gaussian over the oldest kept keyframe and the walls
  // they saw (marginal_prior.hpp). It holds at most this many walls: beyond, the walls no
  // keyframe of the window sees, least recently seen first, are marginalized out of it too
  // (their plan prior stays; what the robot learned of them is forgotten), so that its cost is
  // bounded by what the robot saw lately, not by the building.
  int prior_max_walls = 40;

  // Robust kernels, in sigmas of each factor (residuals are whitened): Huber on measurements.
  double huber_plane_sigmas = 2.0;
  double huber_odometry_sigmas = 3.0;
  double huber_room_sigmas = 2.0;
  // The as-built prior has a Cauchy kernel: a wall is either within its tolerance or built
  // somewhere else, by any amount (a mixture, not a wider Gaussian). With two parallel walls
  // in view, one off its plan, a Gaussian or Huber prior would share the error between them
  // and move the robot; with Cauchy the graph keeps the explanation its history supports.
  double cauchy_wall_prior_sigmas = 1.0;

  int max_iterations = 30;  // Levenberg-Marquardt, per keyframe

  // Loss of track: a keyframe is bad when it matches fewer plan walls than this, or fewer than
  // min_plan_fraction of the x (or of the y) walls it sees (a robot metres off along a
  // corridor still matches the corridor's walls, not those across it), when more than half of
  // its planes disagree after the optimization (squared Mahalanobis residual above
  // loss_mahalanobis2: chi-square, 3 DoF, 99 %; one outlier the robust kernels hold is not a
  // lost robot), or when the optimization moved it more than loss_correction_m from its
  // odometry prediction.
  // This many bad keyframes in a row -> lost; recover_after_keyframes good ones -> tracking.
  int min_plan_associations = 2;
  double min_plan_fraction = 0.5;
  double loss_mahalanobis2 = 11.34;
  double loss_correction_m = 0.5;
  int lost_after_keyframes = 5;
  int recover_after_keyframes = 3;
};

enum class TrackingState { Tracking, Lost };
const char* toString(TrackingState state);

// What became of one observed wall of the scan (by its index in the input).
struct PlaneAssociation {
  enum class Kind {
    PlanWall,   // a face of a plan wall
    NewPlane,   // a plane not in the plan, seen before
    Candidate,  // unmatched; remembered, a new plane once seen often enough
    Rejected,   // unusable (not finite, not vertical)
  };
  int observation = -1;
  Kind kind = Kind::Rejected;
  int wall = -1;       // PlanWall: index into the storey's walls
  int face = -1;       // PlanWall: 0 or 1
  int new_plane = -1;  // NewPlane: id
  double mahalanobis2 = 0;
};

struct SGraphResult {
  Eigen::Isometry3d T_map_base = Eigen::Isometry3d::Identity();
  Eigen::Isometry3d T_map_odom = Eigen::Isometry3d::Identity();
  bool keyframe_added = false;
  int keyframe = -1;  // id of the keyframe added (or the last one)
  std::vector<PlaneAssociation> associations;  // filled when a keyframe was added
  int plan_walls_matched = 0;
  int new_planes_matched = 0;
  int new_planes_created = 0;
  int planes_merged = 0;  // new planes found to duplicate a plan wall (room association)
  int window_keyframes = 0;
  int iterations = 0;
  double initial_cost = 0, final_cost = 0;
  double solve_time_s = 0;
  // Covariance of the newest keyframe's map (x, y, yaw) after the window's optimization
  // (Ceres' marginal covariance); unset between keyframes' solves or when rank deficient.
  std::optional<Eigen::Matrix3d> covariance;
  TrackingState state = TrackingState::Tracking;
  std::vector<std::string> warnings;
};

// A plan wall as estimated: where it stands relative to its plan position.
struct WallDeviation {
  int wall = -1;  // index into the storey's walls
  std::string wall_id;
  double offset_m = 0;     // along faces[0]'s normal
  double angle_deg = 0;    // about its vertical centre line, counter-clockwise
  double thickness_change_m = 0;
  int observations = 0;    // keyframe-plane factors on it so far
};

struct NewPlane {
  int id = -1;
  Eigen::Vector3d normal = Eigen::Vector3d::UnitX();  // map frame, horizontal
  double d = 0;                                       // n·p + d = 0
  Eigen::Vector2d start = Eigen::Vector2d::Zero(), end = Eigen::Vector2d::Zero();  // seen extent
  int observations = 0;
};

struct KeyframeInfo {
  int id = -1;
  double stamp_s = 0;
  Eigen::Isometry3d T_map_base = Eigen::Isometry3d::Identity();
  bool in_window = false;
  int plan_walls = 0;  // plan wall faces it observed
};

struct RoomNode {
  int room = -1;  // index into the storey's rooms
  std::string name;
  bool corridor = false;  // two walls (one pair) instead of four
  Eigen::Vector2d plan_centre = Eigen::Vector2d::Zero();
  Eigen::Vector2d centre = Eigen::Vector2d::Zero();  // estimated
  std::vector<int> walls;
};

class SGraphTracker {
 public:
  // `T_map_odom` from the particle filter at convergence (paper: "When the particle filter
  // provides the initial pose estimation, S-Graphs starts creating its first robot-tracking
  // layer"). Walls the graph cannot use (zero length, not vertical) are named in warnings().
  // The tracker copies what it needs of the storey: it keeps no reference to it.
  SGraphTracker(const bim::Storey& storey, const Eigen::Isometry3d& T_base_lidar, const SGraphConfig& config,
                const Eigen::Isometry3d& T_map_odom);
  ~SGraphTracker();
  SGraphTracker(SGraphTracker&&) noexcept;

  // One scan: the odometry pose and the wall planes in the lidar frame. Never throws for bad
  // input (non-finite pose or plane, jumps): the result's warnings name it.
  SGraphResult addScan(double stamp_s, const Eigen::Isometry3d& T_odom_base, const std::vector<planes::ObservedPlane>& walls);

  // Whether a scan at this odometry pose becomes a keyframe, the only scans whose planes the
  // graph uses: the caller may skip extracting planes for the others and pass none.
  bool wantsObservations(const Eigen::Isometry3d& T_odom_base) const;

  TrackingState state() const;
  Eigen::Isometry3d T_map_odom() const;
  std::vector<WallDeviation> wallDeviations() const;  // walls observed at least once
  std::vector<NewPlane> newPlanes() const;
  std::vector<KeyframeInfo> keyframes() const;        // every keyframe so far, oldest first
  std::vector<RoomNode> rooms() const;
  const std::vector<std::string>& warnings() const;   // from the construction (the plan)

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace bimloc::sgraph
