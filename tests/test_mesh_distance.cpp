// MeshDistance (Embree's point query + exact closest points) against two truths: the analytic
// distance inside a box room, and brute force over every triangle of the default world's storey.
#include "sim/metrics/map_error.hpp"
#include "sim/metrics/mesh_distance.hpp"
#include "sim/world/world.hpp"
#include "sim_fixtures.hpp"

#include <gtest/gtest.h>

#include <random>

using namespace bimloc;

TEST(MeshDistance, InsideABoxItIsTheDistanceToTheNearestFace) {
  const Eigen::Vector3d size(6, 4, 3);
  const sim::MeshDistance box(test::boxRoom(size.cast<float>()));
  std::mt19937_64 rng(3);
  std::uniform_real_distribution<double> u(0.01, 0.99);
  for (int i = 0; i < 500; ++i) {
    const Eigen::Vector3d p(u(rng) * size.x(), u(rng) * size.y(), u(rng) * size.z());
    const double truth = std::min({p.x(), size.x() - p.x(), p.y(), size.y() - p.y(), p.z(), size.z() - p.z()});
    EXPECT_NEAR(box.distance(p), truth, 1e-5) << p.transpose();
  }
  EXPECT_TRUE(std::isinf(box.distance(Eigen::Vector3d(NAN, 0, 0))));
  EXPECT_TRUE(std::isinf(sim::MeshDistance(bim::TriangleMesh{}).distance(Eigen::Vector3d::Zero())));
}

TEST(MeshDistance, EqualsBruteForceOverEveryTriangleOfARealStorey) {
  const auto& storey = test::officeWorld().building().storeys.at(0);
  const sim::MeshDistance fast(storey.mesh);
  std::mt19937_64 rng(5);
  std::uniform_real_distribution<double> x(-2, 30), y(-2, 20), z(-1, 4);
  for (int i = 0; i < 200; ++i) {
    const Eigen::Vector3d p(x(rng), y(rng), z(rng));
    double brute = INFINITY;
    for (const auto& t : storey.mesh.triangles) {
      const Eigen::Vector3d c = sim::closestPointOnTriangle(p, storey.mesh.vertices[t[0]].cast<double>(),
                                                            storey.mesh.vertices[t[1]].cast<double>(),
                                                            storey.mesh.vertices[t[2]].cast<double>());
      brute = std::min(brute, (c - p).norm());
    }
    EXPECT_NEAR(fast.distance(p), brute, 1e-5) << p.transpose();
  }
}

TEST(MapError, ScansFromTheTruePoseFitTheMeshAndAnOffsetPoseDoesNot) {
  // Points on the walls of a box room, seen from its centre: placed with the true pose they lie
  // on the mesh; with the pose 0.3 m off, the x walls' points are 0.3 m off.
  const Eigen::Vector3f size(6, 4, 3);
  bim::Storey storey;
  storey.mesh = test::boxRoom(size);
  std::vector<Eigen::Vector3f> points;  // lidar at (3, 2, 1), identity rotation
  for (int i = 0; i <= 40; ++i) {
    const float s = static_cast<float>(i) / 40.f;
    points.emplace_back(-3.f, -1.5f + 3.f * s, 0.5f);  // wall x = 0
    points.emplace_back(3.f, -1.5f + 3.f * s, 0.5f);   // wall x = 6
  }
  const Eigen::Isometry3d truth(Eigen::Translation3d(3, 2, 1));
  sim::MapError exact(storey, 1), off(storey, 1);
  exact.add(points, truth);
  off.add(points, Eigen::Translation3d(0.3, 0, 0) * truth);
  EXPECT_EQ(exact.points(), points.size());
  EXPECT_NEAR(exact.rmse_m(), 0.0, 1e-5);
  EXPECT_NEAR(off.rmse_m(), 0.3, 1e-5);
  EXPECT_TRUE(std::isnan(sim::MapError(storey).rmse_m()));
}
