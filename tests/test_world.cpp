// The simulated world against analytic geometry and against a second ray caster (Bullet).
#include "sim_fixtures.hpp"
#include "test_support.hpp"

#include "sim/world/world.hpp"

#include <bimloc/bim/geometry2d.hpp>

#include <gtest/gtest.h>

#include <random>

using namespace bimloc;

TEST(World, EmbreeRangesInABoxRoomAreAnalytic) {
  const Eigen::Vector3f size(10, 8, 3);
  const sim::World world = sim::World::fromMesh(test::boxRoomFile(size));
  std::mt19937 rng(1);
  std::uniform_real_distribution<float> u(0.1f, 0.9f);
  std::normal_distribution<float> n(0, 1);
  for (int i = 0; i < 5000; ++i) {
    const Eigen::Vector3f o(u(rng) * size.x(), u(rng) * size.y(), u(rng) * size.z());
    const Eigen::Vector3f d = Eigen::Vector3f(n(rng), n(rng), n(rng)).normalized();
    const sim::RayHit hit = world.castRay(0, o, d, 0.0f, 100.0f);
    ASSERT_TRUE(hit.hit());
    EXPECT_NEAR(hit.range_m, test::boxRange(size.cast<double>(), o.cast<double>(), d.cast<double>()), 1e-3);
    EXPECT_LT(hit.normal.dot(d), 0.0f);  // the normal faces the ray
  }
}

TEST(World, PacketsGiveTheSameHitsAsSingleRays) {
  const sim::World world = sim::World::fromPlan(std::string(BIMLOC_WORLDS_DIR) + "/site_office.ifc");
  std::mt19937 rng(2);
  std::normal_distribution<float> n(0, 1);
  for (int trial = 0; trial < 200; ++trial) {
    Eigen::Vector3f origins[16], dirs[16];
    sim::RayHit packet[16];
    for (int k = 0; k < 16; ++k) {
      origins[k] = Eigen::Vector3f(3.0f, 3.0f + 0.001f * k, 1.0f);
      dirs[k] = Eigen::Vector3f(n(rng), n(rng), 0.3f * n(rng)).normalized();
    }
    world.castRays16(0, origins, dirs, 0.05f, 100.0f, packet);
    for (int k = 0; k < 16; ++k) {
      const sim::RayHit single = world.castRay(0, origins[k], dirs[k], 0.05f, 100.0f);
      ASSERT_EQ(single.hit(), packet[k].hit());
      if (single.hit()) {
        EXPECT_FLOAT_EQ(single.range_m, packet[k].range_m);
      }
    }
  }
}

namespace {

// Rays from random points inside the rooms of a storey, in random directions: Embree and
// Bullet must agree on what they hit and how far.
void compareWithBullet(const sim::World& world, std::size_t storey) {
  const auto& rooms = world.building().storeys[storey].rooms;
  ASSERT_FALSE(rooms.empty());
  std::mt19937 rng(3);
  std::normal_distribution<double> n(0, 1);
  int rays = 0, agree = 0;
  double worst = 0.0;
  for (const auto& room : rooms) {
    Eigen::Vector2d lo = room.footprint[0], hi = lo;
    for (const auto& p : room.footprint) lo = lo.cwiseMin(p), hi = hi.cwiseMax(p);
    std::uniform_real_distribution<double> ux(lo.x(), hi.x()), uy(lo.y(), hi.y());
    for (int i = 0; i < 400; ++i) {
      const Eigen::Vector2d xy(ux(rng), uy(rng));
      if (!bim::pointInPolygon(room.footprint, xy)) continue;
      const Eigen::Vector3d o(xy.x(), xy.y(), room.floor_z + 0.3 + 1.5 * std::abs(std::sin(i + 0.5)));
      const Eigen::Vector3d d = Eigen::Vector3d(n(rng), n(rng), 0.5 * n(rng)).normalized();
      const sim::RayHit e = world.castRay(storey, o.cast<float>(), d.cast<float>(), 0.0f, 50.0f);
      // (origins can lie on a surface, e.g. a table top: a hit at range 0 that Bullet skips)
      const sim::RayHit b = world.bulletRay(storey, o, o + 50.0 * d);
      ++rays;
      if (e.hit() != b.hit()) continue;
      if (e.hit()) worst = std::max(worst, double(std::abs(e.range_m - b.range_m)));
      if (e.hit() && std::abs(e.range_m - b.range_m) > 1e-3) continue;
      ++agree;
    }
  }
  EXPECT_GT(rays, 1000);
  // Agreement: both miss, or both hit within 1 mm. Rays that graze an edge between two
  // triangles, or start on a surface, may differ: at most 1 in 1000.
  EXPECT_GE(agree, rays - rays / 1000) << "disagreements: " << rays - agree << " of " << rays
                                       << ", largest range difference " << worst << " m";
}

}  // namespace

TEST(World, EmbreeAgreesWithBulletOnTheDefaultWorld) {
  compareWithBullet(sim::World::fromPlan(std::string(BIMLOC_WORLDS_DIR) + "/site_office.ifc"), 0);
}

TEST(World, EmbreeAgreesWithBulletOnARealStorey) {
  BIMLOC_REQUIRE_SHARED(path, "AC20-FZK-Haus.ifc");
  compareWithBullet(sim::World::fromPlan(path), 0);
}

TEST(World, SweepsStopAtWallsAndFindTheFloor) {
  const sim::World world = sim::World::fromMesh(test::boxRoomFile({10, 8, 3}));
  EXPECT_TRUE(world.sweepClear(0, {2, 2, 1}, {8, 6, 1}, 0.3));
  Eigen::Vector3d contact;
  EXPECT_FALSE(world.sweepClear(0, {2, 2, 1}, {12, 2, 1}, 0.3, &contact));
  EXPECT_NEAR(contact.x(), 10.0, 1e-3);
  double floor_z = -1;
  ASSERT_TRUE(world.floorBelow(0, {5, 5, 1.2}, 5.0, &floor_z));
  EXPECT_NEAR(floor_z, 0.0, 1e-4);
}

// A body that starts cutting a surface (the Duplex start drawn on a bed) is not free; the
// sweep alone, moving parallel to the surface it already cuts, may not say so.
TEST(World, OverlapTestSeesASphereThatAlreadyCutsASurface) {
  const sim::World world = sim::World::fromMesh(test::boxRoomFile({10, 8, 3}));
  EXPECT_TRUE(world.sphereClear(0, {5, 4, 1.5}, 0.3));
  Eigen::Vector3d contact;
  EXPECT_FALSE(world.sphereClear(0, {9.8, 4, 1.5}, 0.3, &contact));
  EXPECT_NEAR(contact.x(), 10.0, 1e-2);
  EXPECT_FALSE(world.sphereClear(0, {5, 4, 2.85}, 0.3, &contact));
  EXPECT_NEAR(contact.z(), 3.0, 1e-2);
}

TEST(World, LoadsAnExtractFolderLikeThePlan) {
  const sim::World from_dir = sim::World::load(std::string(BIMLOC_WORLDS_DIR) + "/../meshes/site_office");
  const sim::World from_plan = sim::World::load(std::string(BIMLOC_WORLDS_DIR) + "/site_office.ifc");
  ASSERT_EQ(from_dir.storeyCount(), from_plan.storeyCount());
  // The extract folder holds every element; a world built from the plan leaves door leaves out.
  EXPECT_GT(from_dir.triangleCount(0), from_plan.triangleCount(0));
  EXPECT_EQ(from_dir.building().storeys[0].rooms.size(), from_plan.building().storeys[0].rooms.size());
  EXPECT_THROW(from_dir.storeyIndex("Attic"), std::invalid_argument);
}
