// Shared by the filter's measurement tests (face index, wall lines, pose refinement): the
// default world tiled into a larger building, and observations as ParticleFilter::observe
// makes them for a level base.
#pragma once

#include "pf/measurement.hpp"

#include <bimloc/bim/building.hpp>
#include <bimloc/planes/plane_extraction.hpp>

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

namespace bimloc::test {

using pf::detail::Observation;

// The default world tiled k x k (a larger building of the same kind), ids made unique.
inline bim::Storey tiled(const bim::Storey& s, int k) {
  bim::Storey out = s;
  out.walls.clear(), out.rooms.clear();
  for (int i = 0; i < k; ++i)
    for (int j = 0; j < k; ++j) {
      const Eigen::Vector3d t(30.0 * i, 20.0 * j, 0.0);
      const std::string tag = "@" + std::to_string(i) + "," + std::to_string(j);
      for (auto w : s.walls) {
        w.id += tag, w.start += t, w.end += t;
        for (auto& f : w.faces) f.plane.d -= f.plane.n.dot(t), f.start += t, f.end += t;
        out.walls.push_back(w);
      }
      for (auto r : s.rooms) {
        r.id += tag, r.name += tag, r.centre += t.head<2>();
        for (auto& q : r.footprint) q += t.head<2>();
        for (auto& rw : r.walls) rw.wall_id += tag;
        out.rooms.push_back(r);
      }
    }
  return out;
}

// What ParticleFilter::observe does for a level base.
inline std::vector<Observation> observations(const std::vector<planes::ObservedPlane>& walls, const Eigen::Isometry3d& mount) {
  std::vector<Observation> out;
  for (const auto& w : walls) {
    Observation o;
    o.normal_base = mount.linear() * w.normal.normalized();
    o.d_offset = w.d - o.normal_base.dot(mount.translation());
    o.azimuth_base = std::atan2(o.normal_base.y(), o.normal_base.x());
    o.elevation = std::asin(std::clamp(o.normal_base.z(), -1.0, 1.0));
    const Eigen::Vector3d c = mount.linear() * w.centroid + mount.translation();
    o.centroid_base = c.head<2>();
    o.range_m = c.norm();
    out.push_back(o);
  }
  return out;
}

// A vertical plane n.p + d = 0 (map, n towards the robot) seen from the base at `pose`, its
// returns' centroid at `centroid` (map): normal, d, azimuth and centroid as
// ParticleFilter::observe gives them; range from the centroid's horizontal distance.
inline Observation planeSeenFrom(const Eigen::Vector3d& pose, const Eigen::Vector2d& n, double d, const Eigen::Vector2d& centroid) {
  const Eigen::Rotation2Dd to_base(-pose.z());
  Observation o;
  const Eigen::Vector2d nb = to_base * n;
  o.normal_base = Eigen::Vector3d(nb.x(), nb.y(), 0.0);
  o.d_offset = n.dot(pose.head<2>()) + d;
  o.azimuth_base = std::atan2(nb.y(), nb.x());
  o.centroid_base = to_base * (centroid - pose.head<2>());
  o.range_m = o.centroid_base.norm();
  return o;
}

}  // namespace bimloc::test
