// Distance from a point to a triangle mesh: Embree's BVH finds the candidate triangles
// (rtcPointQuery), the closest point on each is exact (Ericson, Real-Time Collision Detection,
// 5.1.5). For the map RMSE against the plan's storey mesh (paper, table "Point cloud RMSE").
#pragma once

#include <bimloc/bim/building.hpp>

#include <Eigen/Core>
#include <memory>

namespace bimloc::sim {

class MeshDistance {
 public:
  explicit MeshDistance(const bim::TriangleMesh& mesh);
  ~MeshDistance();
  MeshDistance(MeshDistance&&) noexcept;

  // Distance to the nearest triangle; +inf for an empty mesh or a non-finite point.
  double distance(const Eigen::Vector3d& p) const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

// Closest point of triangle (a, b, c) to p.
Eigen::Vector3d closestPointOnTriangle(const Eigen::Vector3d& p, const Eigen::Vector3d& a, const Eigen::Vector3d& b,
                                       const Eigen::Vector3d& c);

}  // namespace bimloc::sim
