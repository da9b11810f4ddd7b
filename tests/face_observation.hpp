// A wall face as the plane extraction would report it from a base pose: the one construction
// the path-evidence tests share (test_path_evidence.cpp, test_verdict_bounds.cpp).
#pragma once

#include <bimloc/bim/building.hpp>

#include "pf/measurement.hpp"

#include <Eigen/Core>

#include <cmath>
#include <optional>

namespace bimloc::test {

// The observation of `face` from `base` (map x, y, yaw), exact; nullopt when the base is behind it.
inline std::optional<pf::detail::Observation> observeFace(const bim::WallFace& face, const Eigen::Vector3d& base) {
  const double c = std::cos(base.z()), s = std::sin(base.z());
  Eigen::Matrix2d R;
  R << c, -s, s, c;
  const Eigen::Vector2d n_map = face.plane.n.head<2>().normalized();
  if (n_map.dot(base.head<2>()) + face.plane.d <= 0.0) return std::nullopt;  // seen from behind
  pf::detail::Observation o;
  const Eigen::Vector2d n = R.transpose() * n_map;
  o.normal_base = Eigen::Vector3d(n.x(), n.y(), 0.0);
  o.azimuth_base = std::atan2(n.y(), n.x());
  o.d_offset = face.plane.d + n_map.dot(base.head<2>());
  o.centroid_base = R.transpose() * (0.5 * (face.start + face.end).head<2>() - base.head<2>());
  o.range_m = std::hypot(o.centroid_base.norm(), 1.0);
  return o;
}

}  // namespace bimloc::test
