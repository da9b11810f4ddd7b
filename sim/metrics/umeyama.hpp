// Least-squares similarity between two point sets: S. Umeyama, "Least-squares estimation of
// transformation parameters between two point patterns", IEEE PAMI 13(4), 1991 (eqs. 34-43),
// as evo.core.geometry.umeyama_alignment computes it for `evo_ape -a` (se3) and `-as` (sim3).
#pragma once

#include <Eigen/Geometry>

namespace bimloc::sim {

struct Similarity {
  Eigen::Matrix3d rotation = Eigen::Matrix3d::Identity();
  Eigen::Vector3d translation = Eigen::Vector3d::Zero();
  double scale = 1.0;
  Eigen::Vector3d apply(const Eigen::Vector3d& p) const { return rotation * (scale * p) + translation; }
};

// The similarity (scale 1 unless with_scale) that maps the points `from` (3 x n) best onto
// `to`: min sum |to_i - (s R from_i + t)|^2. Throws std::invalid_argument when the points are
// too few or degenerate (all on a line or a point: the rotation about it is undetermined).
Similarity umeyama(const Eigen::Matrix3Xd& from, const Eigen::Matrix3Xd& to, bool with_scale);

}  // namespace bimloc::sim
