// The converged pose, refined with the sensor's own noise. The filter weighs with wide sigmas
// (sigma_d 0.15 m, and the path evidence wider still for odometry drift over 15 m): wide enough
// for a few thousand particles to find the right place at all, and so wide that a base-cabinet
// or counter front standing 0.6 m before a wall falls inside the gate and pulls the pose a few
// decimetres towards it (the Duplex kitchens: 0.3-0.4 m in y, which the S-Graph then kept).
// Coarse-to-fine, as global localizers hand over to scan matching (AMCL then a scan matcher;
// HDL's branch-and-bound then NDT): once the place is decided, the pose is searched again
// nearby on the last metres of path, with sigma_d from what the error really is there (the
// lidar's range accuracy, the wall's as-built tolerance, the odometry drift over those metres):
// a gate of about 0.25 m, inside which furniture 0.6 m before a wall no longer reaches.
#pragma once

#include "measurement.hpp"

#include <Eigen/Core>
#include <cmath>
#include <limits>
#include <vector>

namespace bimloc::pf::detail {

struct PoseRefinementConfig {
  // Path length of the latest scans the refinement fits: short, so that the odometry's drift
  // across it stays centimetres (legged odometry 2 % of distance: 0.04 m over 2 m).
  double window_m = 2.0;
  // A plane's d from a VLP-16 scan: its range accuracy (datasheet: +-3 cm), an upper bound of
  // a plane fitted to hundreds of returns.
  double range_sigma_m = 0.03;
  // How far the refined pose may lie from the converged one: the bound within which a pose is
  // the same place (the false-convergence bound, 0.5 m); farther is another place, which the
  // path evidence decides, not this.
  double search_m = 0.5;
  double grid_step_m = 0.05;
  // A face does not match a plane in its openings grown by this margin (a window's pane
  // 0.1-0.35 m behind the face, a door leaf): the S-Graph's rule (sgraph.opening_margin_m), for
  // a search as local as its association. The Duplex's living-room windows: panes 0.35 m behind
  // the south wall's face pulled a converged pose 0.49 m north (Level 1, A103 seed 2). The
  // plane is the opening's filling instead, anywhere within the wall's body (measurement.cpp).
  double opening_margin_m = 0.15;
};

// A scan of the window: its odometry pose (x, y, yaw of odom <- base), base height, planes.
struct RefinementScan {
  Eigen::Vector3d odom = Eigen::Vector3d::Zero();
  double z_base = 0;
  const std::vector<Observation>* observations = nullptr;
};

// One scan of the window matched with the base at map <- odom `T_map_odom`, as the local
// search scores it (with a `shortlist` of this scan's faces, through it where it holds the pose:
// the same result; with a finite `floor`, stopped below it as matchObservations is), as the local
// search scores it: every face a candidate, out of rooms not penalised (a doorway is no worse
// a place), a plane in a face's openings grown by `opening_margin_m` not the face but what fills
// them (within the wall's body: no d error), one seen
// through a solid face a contradiction (measurement.hpp). With `per_observation`, each match.
MatchResult matchScanAt(const Eigen::Vector3d& T_map_odom, const RefinementScan& scan, const RoomIndex& every_face,
                        const ParticleFilterConfig& model, double opening_margin_m,
                        std::vector<ObservationMatch>* per_observation = nullptr, const FaceShortlist* shortlist = nullptr,
                        double floor = -std::numeric_limits<double>::infinity());

// Each scan's faces (FaceShortlist) for every pose now within r.search_m of `centre` and
// kShortlistYawRad of its heading: a pose beyond (the pattern search may turn farther) is
// matched through the index, with the same result.
constexpr double kShortlistYawRad = 5.0 * M_PI / 180.0;
std::vector<FaceShortlist> windowShortlists(const Eigen::Vector3d& centre, const Eigen::Vector3d& odom_now,
                                            const std::vector<RefinementScan>& scans, const RoomIndex& every_face,
                                            const ParticleFilterConfig& model, const PoseRefinementConfig& r);

// The offsets of the local search's grid (step r.grid_step_m) from `min_m` out to r.search_m,
// nearest first (of poses that fit alike, the nearest is met first).
std::vector<Eigen::Vector2d> gridOffsets(const PoseRefinementConfig& r, double min_m = 0.0);

// The tight error model: `filter`'s angular sigmas and gate, sigma_d from the lidar, the plan
// tolerance and the odometry drift over the window (config.evidence_*).
ParticleFilterConfig refinementModel(const ParticleFilterConfig& filter, const PoseRefinementConfig& r = {});

// The pose now (map x, y, yaw, at odometry pose `odom_now`) within r.search_m of `converged`
// that the scans fit best under refinementModel, every face of `every_face` (built without the
// room factor) a candidate. Of poses that fit alike, the one nearest `converged` (a grid
// searched from the centre out, then a pattern search on x, y, yaw).
Eigen::Vector3d refinePose(const Eigen::Vector3d& converged, const Eigen::Vector3d& odom_now,
                           const std::vector<RefinementScan>& scans, const RoomIndex& every_face,
                           const ParticleFilterConfig& model, const PoseRefinementConfig& r = {});

}  // namespace bimloc::pf::detail
