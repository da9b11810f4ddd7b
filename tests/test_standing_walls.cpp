// The walls each storey's map holds (bim/standing_walls.hpp): a split level's walls, filed under
// one storey, stand beside the floor of another. Built in code, the answers known by geometry.
#include "bim/extraction.hpp"
#include "sgraph_fixtures.hpp"

#include <bimloc/bim/standing_walls.hpp>
#include <bimloc/localizer.hpp>

#include <gtest/gtest.h>

#include <algorithm>

using namespace bimloc::bim;

namespace {

// A straight wall start -> end, 0.2 m thick, standing from z0 up h.
Wall wall(const std::string& id, Eigen::Vector2d s, Eigen::Vector2d e, double z0, double h) {
  return bimloc::test::liftedWall(bimloc::test::boxWall(id, s, e, 0.2), z0, h);
}

Room room(const std::string& name, double x0, double y0, double x1, double y1, double z0, double h) {
  Room r;
  r.id = r.name = name;
  r.footprint = {{x0, y0}, {x1, y0}, {x1, y1}, {x0, y1}};
  r.area_m2 = (x1 - x0) * (y1 - y0);
  r.centre = {0.5 * (x0 + x1), 0.5 * (y0 + y1)};
  r.floor_z = z0, r.height_m = h;
  return r;
}

std::vector<std::string> ids(const Storey& s) {
  std::vector<std::string> out;
  for (const auto& w : s.walls) out.push_back(w.id);
  return out;
}

// Level 0 (floor 0.0): a room [0, 4] x [0, 3] in four 2.6 m walls. The half level (floor 0.9):
// a room [4.2, 8] x [0, 3] east of it, walled on three sides by its own 2.0 m walls; its west
// side is level 0's east wall, which the file files under level 0. Level 1 (floor 3.0): one
// wall, above both.
Building splitLevel() {
  Building b;
  Storey l0, half, l1;
  l0.id = l0.name = "level 0", l0.elevation_m = 0.0;
  l0.walls = {wall("0S", {-0.2, -0.1}, {4.2, -0.1}, 0.0, 2.6), wall("0E", {4.1, -0.2}, {4.1, 3.2}, 0.0, 2.6),
              wall("0N", {4.2, 3.1}, {-0.2, 3.1}, 0.0, 2.6), wall("0W", {-0.1, 3.2}, {-0.1, -0.2}, 0.0, 2.6)};
  l0.rooms = {room("R0", 0, 0, 4, 3, 0.0, 2.6)};
  half.id = half.name = "half level", half.elevation_m = 0.9;
  half.walls = {wall("HS", {4.0, -0.1}, {8.2, -0.1}, 0.9, 2.0), wall("HE", {8.1, -0.2}, {8.1, 3.2}, 0.9, 2.0),
                wall("HN", {8.2, 3.1}, {4.0, 3.1}, 0.9, 2.0)};
  half.rooms = {room("RH", 4.2, 0, 8, 3, 0.9, 2.0)};
  l1.id = l1.name = "level 1", l1.elevation_m = 3.0;
  l1.walls = {wall("1S", {0, 5}, {8, 5}, 3.0, 2.6)};
  l1.rooms = {room("R1", 0, 5, 8, 9, 3.0, 2.6)};
  for (auto* s : {&l0, &half, &l1})
    for (auto& r : s->rooms) detail::linkRoomByGeometry(r, s->walls, ExtractOptions{});
  b.storeys = {l0, half, l1};
  return b;
}

}  // namespace

TEST(StandingWalls, ASplitLevelsWallsStandInTheStoreyWhoseBandTheyCross) {
  const Building plan = splitLevel();
  StandingWallsReport report;
  const Building sensed = withStandingWalls(plan, {}, &report);
  ASSERT_EQ(sensed.storeys.size(), 3u);
  // Level 0's band is 0.3-1.8 m: the half level's walls (0.9-2.9 m) cross it.
  EXPECT_EQ(ids(sensed.storeys[0]), (std::vector<std::string>{"0S", "0E", "0N", "0W", "HS", "HE", "HN"}));
  // The half level's band is 1.2-2.7 m: level 0's walls (0-2.6 m) cross it; level 1's (3.0 m up) do not.
  EXPECT_EQ(ids(sensed.storeys[1]), (std::vector<std::string>{"HS", "HE", "HN", "0S", "0E", "0N", "0W"}));
  // Level 1's band is 3.3-4.8 m: nothing below reaches it (the half level's walls end at 2.9 m).
  EXPECT_EQ(ids(sensed.storeys[2]), (std::vector<std::string>{"1S"}));
  EXPECT_EQ(report.added, (std::vector<std::size_t>{3, 4, 0}));
  EXPECT_EQ(report.total(), 7u);
  // The added walls are the same walls: geometry and height as filed.
  const Wall* e = sensed.storeys[1].findWall("0E");
  ASSERT_NE(e, nullptr);
  EXPECT_DOUBLE_EQ(e->start.z(), 0.0);
  EXPECT_DOUBLE_EQ(e->height_m, 2.6);
}

TEST(StandingWalls, TheHalfLevelsRoomIsLinkedToTheWallOfTheLevelBelowThatBoundsIt) {
  const Building plan = splitLevel();
  // As filed, the half level's room has three walls: its west side is another storey's wall.
  ASSERT_EQ(plan.storeys[1].rooms[0].walls.size(), 3u);
  const Building sensed = withStandingWalls(plan);
  const Room& rh = sensed.storeys[1].rooms[0];
  const auto west = std::find_if(rh.walls.begin(), rh.walls.end(), [](const RoomWall& w) { return w.wall_id == "0E"; });
  ASSERT_NE(west, rh.walls.end()) << "level 0's east wall bounds the half level's room";
  const Wall* e = sensed.storeys[1].findWall("0E");
  ASSERT_GE(west->face, 0);
  // The face looking into the room (x = 4.2, normal +x), not the one facing level 0's room.
  EXPECT_GT(e->faces[static_cast<std::size_t>(west->face)].plane.n.x(), 0.99);
  // Level 0's room gains no wall of the half level: none lies on its footprint.
  EXPECT_EQ(sensed.storeys[0].rooms[0].walls.size(), plan.storeys[0].rooms[0].walls.size());
  // The half level's other walls are linked as before, first.
  for (std::size_t i = 0; i < 3; ++i) EXPECT_EQ(rh.walls[i].wall_id, plan.storeys[1].rooms[0].walls[i].wall_id);
}

TEST(StandingWalls, StoreysThatDoNotOverlapComeBackAsFiled) {
  Building plan = splitLevel();
  plan.storeys.erase(plan.storeys.begin() + 1);  // level 0 and level 1 only: 3 m apart
  StandingWallsReport report;
  const Building sensed = withStandingWalls(plan, {}, &report);
  ASSERT_EQ(sensed.storeys.size(), plan.storeys.size());
  for (std::size_t s = 0; s < plan.storeys.size(); ++s) {
    EXPECT_EQ(ids(sensed.storeys[s]), ids(plan.storeys[s]));
    ASSERT_EQ(sensed.storeys[s].rooms.size(), plan.storeys[s].rooms.size());
    EXPECT_EQ(sensed.storeys[s].rooms[0].walls.size(), plan.storeys[s].rooms[0].walls.size());
    EXPECT_EQ(sensed.storeys[s].elevation_m, plan.storeys[s].elevation_m);
  }
  EXPECT_EQ(report.total(), 0u);
}

TEST(StandingWalls, AWallOfUnknownHeightStaysInItsOwnStorey) {
  // Height 0 is "not known": a map face where no wall stands would count against the true pose.
  Building plan = splitLevel();
  plan.storeys[1].walls[0].height_m = 0.0;
  const Building sensed = withStandingWalls(plan);
  EXPECT_EQ(sensed.storeys[0].findWall("HS"), nullptr);
  EXPECT_NE(sensed.storeys[0].findWall("HE"), nullptr);
  EXPECT_NE(sensed.storeys[1].findWall("HS"), nullptr);
}

TEST(StandingWalls, TheLocalizerSearchesInTheStandingWallsAndSaysSo) {
  const Building plan = splitLevel();
  const auto said = [](const bimloc::Localizer& l, const std::string& what) {
    for (const auto& w : l.warnings())
      if (w.find(what) != std::string::npos) return true;
    return false;
  };
  bimloc::LocalizerConfig config;
  config.storey = "half level";
  const bimloc::Localizer standing(plan, Eigen::Isometry3d::Identity(), config);
  EXPECT_TRUE(said(standing, "storey 'half level': 4 walls filed under other storeys stand in its wall band"));
  EXPECT_TRUE(said(standing, "storey 'level 0': 3 walls"));
  config.storeys.standing_walls = false;  // the walls as filed
  const bimloc::Localizer filed(plan, Eigen::Isometry3d::Identity(), config);
  EXPECT_TRUE(filed.warnings().empty());
}
