// A fan of rays from one point (a predicted planar scan), each cast only against the segments it
// can meet. castRay tries every segment near the pose for every ray: 90 rays against some 150
// segments at each of the guide's trial goals in every place made the rays most of its cost.
#pragma once

#include "wall_slice.hpp"

#include <Eigen/Core>

#include <vector>

namespace bimloc::guide::detail {

class RayFan {
 public:
  // The rays from `origin` at heading + 2 pi k / rays (k = 0 .. rays - 1), up to max_m.
  // Per ray, the segments of `segments` (kept by reference) that it can meet, in their order:
  // - those whose angle from the origin, widened by kMarginRad, holds the ray's, within
  //   max_m + kMarginM of the origin;
  // - those the ray runs nearly along (within kMarginRad), where castRay's intersection is
  //   ill-conditioned;
  // - those within kNearM of the origin, for every ray.
  // castRay's test on any other segment fails at any best <= max_m: see ray_fan.cpp.
  RayFan(const std::vector<Segment2>& segments, const Eigen::Vector2d& origin, double heading, int rays, double max_m);

  // castRay(segments, origin, direction, max_m, wall) for ray k (`direction` that ray's unit
  // vector, max_m at most the fan's): the same value and wall.
  double cast(int k, const Eigen::Vector2d& origin, const Eigen::Vector2d& direction, double max_m, int* wall = nullptr) const;

  static constexpr double kMarginRad = 1e-4;
  static constexpr double kMarginM = 1e-6;
  static constexpr double kNearM = 1e-3;

 private:
  const std::vector<Segment2>* segments_;
  std::vector<int> first_;  // per ray, where its segments start in order_ (rays + 1 entries)
  std::vector<int> order_;  // indices into segments_, ray after ray, each ray's in increasing order
};

}  // namespace bimloc::guide::detail
