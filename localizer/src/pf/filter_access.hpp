// What StoreyBank needs of a ParticleFilter beyond its public face: its path evidence, to
// weigh the best place of one storey against the best places of the others by the same
// per-face rule the filter uses within a storey.
#pragma once

#include "path_evidence.hpp"

#include <bimloc/pf/particle_filter.hpp>

namespace bimloc::pf::detail {

struct FilterAccess {
  // The filter's window fitted with the base at `map_pose` now.
  static PathEvidence::WindowFit windowFit(const ParticleFilter& filter, const Pose2& map_pose);
  // Every pose the scan `walls` fits on the filter's storey joins its path candidates
  // (PathEvidence::proposeEveryFit), then the verdict: its best place cannot be missing.
  static PathVerdict everyFitVerdict(ParticleFilter& filter, const std::vector<planes::ObservedPlane>& walls);
  // The places `report` (the filter's latest weighed update, not converged) lists, path_best
  // and path_rivals, each fitted again within its place as the converged pose is: the latest
  // scans under the sensor's own noise (pose_refinement.hpp), a place that lands on one listed
  // before it dropped. The path evidence fits its candidates under the window's wide model
  // (drift over 15 m: sigma_d 0.22 m, a gate of 0.73 m), wide enough for a shelf or counter
  // front a few decimetres before a wall to pull them; the filter decides with them as they
  // are (this runs after its update, on the report a user reads), this only says where each
  // place is. Nothing changes once the filter has converged.
  static void fitPlaces(const ParticleFilter& filter, UpdateReport& report);
};

}  // namespace bimloc::pf::detail
