// A storey larger than 200 m x 200 m: a 600-room office floor (worldgen), whose corridor walls
// hold 150 doors each. Before, its reading took 52 s (IFC++ cut each wall's doors one at a
// time, re-meshing the wall each time: own_opening_cuts.hpp) and the simulator refused it (its
// path grid of 5 cm cells was capped at 16 M cells, 200 m square). Checked against the
// generator's walls and rooms, and by the simulator's planner walking the floor's length.
// ChunkedCells, the path grid's storage, against a plain vector.
#include "plan_checks.hpp"
#include "spec_compare.hpp"
#include "test_support.hpp"

#include "sim/base/chunked_cells.hpp"
#include "sim/base/free_space.hpp"
#include "sim/base/motion_config.hpp"
#include "sim/world/world.hpp"
#include "sim/worldgen/ifc4_writer.hpp"
#include "sim/worldgen/random_world.hpp"

#include <bimloc/bim/ifc_reader.hpp>

#include <gtest/gtest.h>

#include <algorithm>
#include <fstream>
#include <random>
#include <vector>

using namespace bimloc;

TEST(ChunkedCells, HoldsWhatAPlainVectorHolds) {
  std::mt19937 rng(38);
  for (const std::size_t n : {std::size_t{1}, std::size_t{1023}, std::size_t{1024}, std::size_t{1025}, std::size_t{70001}}) {
    sim::ChunkedCells<int> cells(n, -1);
    std::vector<int> plain(n, -1);
    std::uniform_int_distribution<std::size_t> at(0, n - 1);
    for (int k = 0; k < 500; ++k) {
      const std::size_t c = at(rng);
      const int v = static_cast<int>(rng() % 1000);
      cells.at(c) = v, plain[c] = v;
    }
    for (std::size_t c = 0; c < n; ++c) ASSERT_EQ(cells[c], plain[c]) << n << " cells, cell " << c;
    // forEachWritten: every cell written to, in order, within the size, each once.
    std::vector<int> seen(n, 0);
    std::size_t last = 0;
    bool first = true;
    cells.forEachWritten([&](std::size_t c, int v) {
      ASSERT_LT(c, n);
      if (!first) {
        ASSERT_GT(c, last);
      }
      first = false, last = c;
      ++seen[c];
      EXPECT_EQ(v, plain[c]);
    });
    for (std::size_t c = 0; c < n; ++c)
      if (plain[c] != -1) {
        EXPECT_EQ(seen[c], 1) << c;
      }
    cells.clear();
    for (std::size_t c = 0; c < n; ++c) ASSERT_EQ(cells[c], -1);
  }
}

TEST(LargeStorey, ASixHundredRoomFloorIsReadAsGeneratedAndWalkedEndToEnd) {
  const auto spec = worldgen::randomWorld(38001, {worldgen::RandomStyle::Office, 600});
  const std::string path = test::tempDir("large_storey") + "/" + spec.name + ".ifc";
  std::ofstream(path) << worldgen::writeIfc4(spec);

  const bim::Building building = bim::readIfc(path);
  test::SpecTolerance tolerance;
  tolerance.thickness_m = tolerance.axis_m = tolerance.face_m = tolerance.vertex_m = 1e-4;
  tolerance.area_m2 = 1e-2;  // the corridor's 2 280 m2, its outline read in float: 1.6e-3 off
  test::expectStoreysMatch(spec, building);
  test::expectWallsMatch(spec, building, tolerance);
  test::expectRoomsMatch(spec, building, tolerance);

  // The storey's extent is over the old 200 m x 200 m cap; the two rooms with a door farthest
  // apart are over 200 m apart.
  const sim::World world = sim::World::fromPlan(path);
  const auto& rooms = world.building().storeys.at(0).rooms;
  Eigen::Vector2d lo = rooms.front().centre, hi = lo;
  for (const auto& r : rooms) lo = lo.cwiseMin(r.centre), hi = hi.cwiseMax(r.centre);
  ASSERT_GT((hi.x() - lo.x()) * (hi.y() - lo.y()), 200.0 * 150.0);
  std::vector<const bim::Room*> with_door;
  for (const auto& [i, j] : test::doorRooms(spec.storeys.at(0)))
    for (const int r : {i, j})
      if (r >= 0) with_door.push_back(world.building().storeys.at(0).findRoom(spec.storeys.at(0).rooms.at(r).name));
  std::sort(with_door.begin(), with_door.end());
  with_door.erase(std::unique(with_door.begin(), with_door.end()), with_door.end());
  ASSERT_FALSE(with_door.empty());
  ASSERT_TRUE(std::find(with_door.begin(), with_door.end(), nullptr) == with_door.end());
  const bim::Room* start_room = with_door.front();
  const bim::Room* goal_room = start_room;
  for (const bim::Room* r : with_door)
    for (const bim::Room* q : with_door)
      if ((r->centre - q->centre).norm() > (start_room->centre - goal_room->centre).norm()) start_room = r, goal_room = q;
  ASSERT_GT((start_room->centre - goal_room->centre).norm(), 200.0);
  const bim::Room& start = *start_room;
  const bim::Room& goal = *goal_room;
  sim::FreeSpace space(world, 0, sim::MotionConfig{}.body_radius_m,
                       sim::bodyCentreZ(world, 0, start.centre, sim::GaitConfig{}.body_height_m));
  const auto from = space.freeSpotNear(start.centre, &start.footprint, 3.0), to = space.freeSpotNear(goal.centre, &goal.footprint, 3.0);
  ASSERT_TRUE(from && to);
  const auto corners = space.path(*from, *to);
  ASSERT_GE(corners.size(), 2u) << "no path from " << start.name << " to " << goal.name;
  EXPECT_EQ((corners.front() - *from).norm(), 0.0);
  EXPECT_EQ((corners.back() - *to).norm(), 0.0);
  // Every leg clear of the building (the planner's own check, with the body's radius).
  for (std::size_t k = 1; k < corners.size(); ++k) EXPECT_TRUE(space.segmentClear(corners[k - 1], corners[k], 0.0)) << k;
}
