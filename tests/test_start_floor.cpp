// The floor a base stands on at its start (sim/base/free_space.hpp, bodyCentreZ): the floor,
// not the furniture on it. A room built in code, 8 x 6 m, the slab's top at z 0, with a coffee
// table (1.0 x 0.6 m, top 0.38 m: the Duplex's A102 start of `run --all-rooms`, seed 1, stood on
// one and its whole run was planned 0.37 m high, docs/results/2026-11-27-h28duplex.md), a bed
// (2.0 x 1.6 m, top 0.45 m) and a rug 0.02 m thick. The truths are the boxes' own heights.
#include "sim/base/base_trajectory.hpp"
#include "sim/base/free_space.hpp"
#include "sim/world/world.hpp"

#include <gtest/gtest.h>

#include <array>
#include <cstdint>

namespace bimloc::sim {
namespace {

constexpr double kBodyHeightM = 0.5;  // GaitConfig's default

void addStartFloorBox(bim::TriangleMesh& mesh, const Eigen::Vector3d& lo, const Eigen::Vector3d& hi) {
  const auto base = static_cast<std::uint32_t>(mesh.vertices.size());
  for (int i = 0; i < 8; ++i)
    mesh.vertices.emplace_back(float(i & 1 ? hi.x() : lo.x()), float(i & 2 ? hi.y() : lo.y()), float(i & 4 ? hi.z() : lo.z()));
  static constexpr std::array<std::array<std::uint32_t, 4>, 6> kFaces{
      {{0, 2, 3, 1}, {4, 5, 7, 6}, {0, 1, 5, 4}, {2, 6, 7, 3}, {0, 4, 6, 2}, {1, 3, 7, 5}}};
  for (const auto& f : kFaces) {
    mesh.triangles.push_back({base + f[0], base + f[1], base + f[2]});
    mesh.triangles.push_back({base + f[0], base + f[2], base + f[3]});
  }
}

// finish_m: the finished floor's top above the storey's elevation (the slab is under it).
World furnishedRoom(double finish_m = 0.0) {
  bim::Storey s;
  s.id = "S0", s.name = "Ground", s.elevation_m = 0.0;
  bim::Room room;
  room.id = room.name = "Living";
  room.footprint = {{0, 0}, {8, 0}, {8, 6}, {0, 6}};
  room.area_m2 = 48, room.centre = {4, 3}, room.floor_z = 0.0, room.height_m = 3.0;
  s.rooms.push_back(room);
  addStartFloorBox(s.mesh, {-0.2, -0.2, -0.2}, {8.2, 6.2, finish_m});  // slab and finish
  addStartFloorBox(s.mesh, {-0.2, -0.2, 0.0}, {0.0, 6.2, 3.0});        // walls
  addStartFloorBox(s.mesh, {8.0, -0.2, 0.0}, {8.2, 6.2, 3.0});
  addStartFloorBox(s.mesh, {-0.2, -0.2, 0.0}, {8.2, 0.0, 3.0});
  addStartFloorBox(s.mesh, {-0.2, 6.0, 0.0}, {8.2, 6.2, 3.0});
  addStartFloorBox(s.mesh, {3.5, 2.7, finish_m}, {4.5, 3.3, finish_m + 0.38});  // coffee table
  addStartFloorBox(s.mesh, {0.5, 4.0, finish_m}, {2.5, 5.6, finish_m + 0.45});  // bed
  addStartFloorBox(s.mesh, {5.5, 0.5, finish_m}, {7.5, 2.5, finish_m + 0.02});  // rug
  bim::Building b;
  b.file = "furnished room (test)";
  b.storeys = {s};
  return World::fromBuilding(std::move(b));
}

TEST(StartFloor, OnTheFloorOrARugTheBodyStandsOnIt) {
  const World world = furnishedRoom();
  EXPECT_NEAR(bodyCentreZ(world, 0, {6.5, 4.5}, kBodyHeightM), kBodyHeightM, 1e-4);
  EXPECT_NEAR(bodyCentreZ(world, 0, {6.5, 1.5}, kBodyHeightM), 0.02 + kBodyHeightM, 1e-4);  // a finish is the floor
}

TEST(StartFloor, OnATableOrABedTheFloorIsStillTheFloor) {
  const World world = furnishedRoom();
  // The first surface under the spot is the table's top, or the bed's...
  double first = 0.0;
  ASSERT_TRUE(world.floorBelow(0, {4.0, 3.0, kBodyHeightM}, kBodyHeightM + 1.0, &first));
  EXPECT_NEAR(first, 0.38, 1e-4);
  ASSERT_TRUE(world.floorBelow(0, {1.5, 4.8, kBodyHeightM}, kBodyHeightM + 1.0, &first));
  EXPECT_NEAR(first, 0.45, 1e-4);
  // ... the floor the body stands on is the room's.
  EXPECT_NEAR(bodyCentreZ(world, 0, {4.0, 3.0}, kBodyHeightM), kBodyHeightM, 1e-4);
  EXPECT_NEAR(bodyCentreZ(world, 0, {1.5, 4.8}, kBodyHeightM), kBodyHeightM, 1e-4);
}

TEST(StartFloor, AFinishedFloorAboveTheStoreysElevationIsTheFloor) {
  // Every surface 0.15 m above the elevation (a screed the plan's elevation leaves out): the
  // floor, not something standing on it; the table on it is still the table.
  const World world = furnishedRoom(0.15);
  EXPECT_NEAR(bodyCentreZ(world, 0, {6.5, 4.5}, kBodyHeightM), 0.15 + kBodyHeightM, 1e-4);
  EXPECT_NEAR(bodyCentreZ(world, 0, {4.0, 3.0}, kBodyHeightM), 0.15 + kBodyHeightM, 1e-4);
}

TEST(StartFloor, AStartOnATableIsRefusedOneBesideItStandsOnTheFloor) {
  const World world = furnishedRoom();
  const MotionConfig stand;  // Stand
  // The body, on the floor, cuts the table: no room for it there (before, it was planned
  // standing on the table top, 0.38 m up, for the whole run).
  EXPECT_THROW(BaseTrajectory::plan(world, 0, {4.0, 3.0, 0.0}, stand, 5.0, 0), MotionError);
  const BaseTrajectory beside = BaseTrajectory::plan(world, 0, {4.0, 1.5, 0.0}, stand, 5.0, 0);
  EXPECT_NEAR(beside.T_map_base(0.0).translation().z(), kBodyHeightM, 1e-6);
}

}  // namespace
}  // namespace bimloc::sim
