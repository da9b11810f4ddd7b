// The particle weight (paper, "Data Association" and "Update"): observed wall planes moved
// into the map by the particle's pose, associated by class (x / y) and Mahalanobis distance
// in (azimuth, elevation, d) with the faces of the particle's room only.
#pragma once

#include "room_index.hpp"

#include <bimloc/pf/particle_filter.hpp>

#include <cmath>
#include <limits>
#include <vector>

namespace bimloc::pf::detail {

// An observation in the yaw-free base frame (gravity-aligned, at the base's origin): what
// every particle shares, so each particle only applies its yaw and position.
struct Observation {
  Eigen::Vector3d normal_base;  // the observed normal, rotated into the yaw-free base frame
  double d_offset = 0;          // d_L - n_B · (lidar position in the yaw-free base frame)
  double azimuth_base = 0;      // atan2 of normal_base: a particle's yaw just adds to it
  double elevation = 0;         // asin(n_z): the same for every particle
  Eigen::Vector2d centroid_base = Eigen::Vector2d::Zero();  // of its points, x y in the yaw-free base frame
  double range_m = 0;  // 3D distance of the centroid from the base's origin (bounds where a match can lie)
  // The plane's support (ObservedPlane::inliers, voxels): what a piece weighs within its surface
  // in the local search (matchObservations).
  double support = 1.0;
  double extent_m = 0;  // the support's span along the plane, horizontally (0: unknown)
  // Where along the plane its support stands as a wall (ObservedPlane::wall_span_m): length,
  // and middle x y in the yaw-free base frame (not finite: unknown, no check along the line).
  double wall_span_m = 0;
  Eigen::Vector2d span_middle_base = Eigen::Vector2d::Constant(std::numeric_limits<double>::quiet_NaN());
  // The heights its points span, above the base's origin (yaw-free base frame): the centroid's
  // height -+ half the support's vertical extent; unbounded when the extraction gave none.
  double z_low = -std::numeric_limits<double>::infinity();
  double z_high = std::numeric_limits<double>::infinity();
  // Whether a run of its span past the end of its wall line is scored (match_wall_ends): where
  // no two planes of its scan are at an angle (positionFixedByPlanes), the walls' ends are all
  // that fix the position along them. Where two are, the planes fix it; a span's end, placed by
  // the window's drift and the extraction's 0.1 m bins, only adds noise to what they say.
  bool end_scored = false;
};

// Whether two planes are at an angle that fixes a position: 30-150 degrees apart (nearly
// parallel planes fix none). The pose hypotheses' pairs (hypotheses.cpp) and the test below.
bool atPairAngle(const Observation& a, const Observation& b);
// Whether two of a scan's planes are at such an angle: when not, the planes all run one way.
bool positionFixedByPlanes(const std::vector<Observation>& observations);

// Whether the observed plane's points lie at heights the face has (within kVerticalMarginM),
// for a base at map height z_base.
inline bool atFaceHeight(const Observation& o, const Landmark& l, double z_base) {
  return z_base + o.z_high >= l.z_bottom - kVerticalMarginM && z_base + o.z_low <= l.z_top + kVerticalMarginM;
}

struct MatchResult {
  double log_likelihood = 0;
  int associated = 0;
  bool below_floor = false;  // stopped early: the log-likelihood would end below the floor
};

// What each observation matched: the face's id (Landmark::id), -1 for clutter; and its
// squared Mahalanobis distance (the gate for clutter).
struct ObservationMatch {
  int face = -1;
  float m2 = 0;
  bool filling = false;  // matched as what fills the face's openings (a pane, a shut door), not the face
};

// The faces one scan's observations can match, or be hidden behind, at any pose of a region
// (within xy_radius_m of centre's x y and yaw_radius of its yaw), for a local search that
// scores many poses of one scan (the refinement's grid and pattern search): the faces near
// each observation found once for the region, less those its angle or height rules out at
// every pose of it, instead of a query of the face index per pose. A superset of what
// matchObservations visits at each such pose, and its choice among faces does not depend on
// their order (ties go to the fine index's order, visitsBefore), so the match is the same
// bits. Only for a RoomIndex without the room factor (every face a candidate), as the local
// search's is.
struct FaceShortlist {
  Eigen::Vector3d centre = Eigen::Vector3d::Zero();
  double xy_radius_m = 0, yaw_radius = 0;
  std::vector<std::vector<const Landmark*>> match, hide;  // per observation
  std::vector<double> radius_m;  // per observation: its match radius (matchRadius), the same at every pose
  bool holds(const Particle& p) const {
    return std::hypot(p.x - centre.x(), p.y - centre.y()) <= xy_radius_m && std::abs(wrapAngle(p.yaw - centre.z())) <= yaw_radius;
  }
};
FaceShortlist shortlistFaces(const Eigen::Vector3d& centre, double xy_radius_m, double yaw_radius, double z_base,
                             const std::vector<Observation>& observations, const RoomIndex& every_face,
                             const ParticleFilterConfig& config, double opening_margin_m);

// With `out_of_rooms_penalised` false, a pose outside every room is matched like any other
// (against every face, which needs a RoomIndex without the room factor).
// With opening_margin_m >= 0, a face does not match a plane whose support (centroid -+ half
// its extents, along and up) lies inside the face's openings grown by that margin (side by side: one hole): a
// window's pane or a door leaf, parallel to the face and a few decimetres behind it, is not
// the face. And a plane seen behind a face's solid part (see behindSolidFace in the .cpp) costs
// twice the gate: the clutter it is and the face that should have hidden it.
// Only for a local search (the converged pose's refinement): in the global search,
// refusing the pane rewards poses shifted along the wall until it leaves the window and
// matches (FZK-Haus long walks, 6 of 6 localized fell to 4 of 6 when tried).
// With a finite `floor`, the match stops (below_floor) as soon as the log-likelihood summed so
// far is below it: each observation adds a term <= 0, and in floating point a sum never grows
// by adding one, so the whole would be below it too. Otherwise the result is the same bits.
// In the local search (opening_margin_m >= 0) the floor is checked once, at the end: a piece
// joining a surface can lower the surface's mean cost, so no partial sum bounds the whole.
// With a `shortlist` (built from these observations, z_base, rooms and config, holding the
// particle), the faces are taken from it: the same result, faster (see FaceShortlist).
MatchResult matchObservations(const Particle& particle, double z_base, const std::vector<Observation>& observations,
                              const RoomIndex& rooms, const ParticleFilterConfig& config,
                              std::vector<ObservationMatch>* per_observation = nullptr, bool out_of_rooms_penalised = true,
                              double floor = -std::numeric_limits<double>::infinity(),
                              double opening_margin_m = -1.0, const FaceShortlist* shortlist = nullptr);

}  // namespace bimloc::pf::detail
