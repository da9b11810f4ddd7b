// Whether the pose within the decided place is settled. The path evidence decides between
// places (more than 0.5 m or 10 deg apart); within one, furniture can fake the walls: in a
// kitchen whose north wall is hidden behind a row of tall cabinets 0.35 m before it, and with
// something standing 0.3 m before the south wall, the pose 0.33 m north explains both planes
// as walls, and only a plane seen now and then through the south wall (impossible there)
// speaks for the truth (the Duplex, Level 1, A103). Summed scan by scan, the window prefers the
// wrong pose by 27; counted once per wall face, as the path evidence counts, the two are
// level. The same rule as between places: the refined pose must explain the window better,
// by the evidence bar, than every pose farther from it than the convergence radius.
#pragma once

#include "pose_refinement.hpp"

namespace bimloc::pf::detail {

struct LocalMargin {
  double margin = 0;  // of the refined pose over the closest rival within the place (+inf: none)
  Eigen::Vector3d rival = Eigen::Vector3d::Zero();  // that rival, map x, y, yaw now
};

// The margin of `refined` (map pose now, at odometry pose `odom_now`) over every pose of the
// refinement's grid between `min_m` and r.search_m from it (same yaw), on the refinement's
// scans and model, counted once per distinct face (FaceMargin). Stops early once a rival is
// found within `enough` (the bar): the caller asks only whether the pose is settled.
LocalMargin localMargin(const Eigen::Vector3d& refined, const Eigen::Vector3d& odom_now, const std::vector<RefinementScan>& scans,
                        const RoomIndex& every_face, const ParticleFilterConfig& model, const PoseRefinementConfig& r, double min_m,
                        double enough);

}  // namespace bimloc::pf::detail
