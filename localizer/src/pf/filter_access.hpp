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
};

}  // namespace bimloc::pf::detail
