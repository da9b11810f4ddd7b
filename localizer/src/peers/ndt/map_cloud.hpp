// The NDT peer's map: points sampled from a storey mesh, and its horizontal slices. Private to
// the library (no PCL here).
#pragma once

#include <bimloc/bim/building.hpp>

#include <Eigen/Core>
#include <vector>

namespace bimloc::peers {

using Cloud3 = std::vector<Eigen::Vector3f>;
using Cloud2 = std::vector<Eigen::Vector2f>;

// Points on every triangle of `mesh`, about spacing_m apart: rows parallel to the longest edge,
// spacing_m apart, each sampled every spacing_m (so a thin sliver costs its area, not its
// longest edge squared). Deterministic: a lattice, in mesh order, no random numbers.
Cloud3 sampleMesh(const bim::TriangleMesh& mesh, double spacing_m);

// The xy of the points whose z is strictly inside (min_z, max_z) (hdl_global_localization's slice).
Cloud2 sliceBand(const Cloud3& points, double min_z, double max_z);

}  // namespace bimloc::peers
