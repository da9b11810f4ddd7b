// Where to look next (localizer/guide/, issue 28 §4) and the base that follows it
// (sim/runner/guided_walk.hpp, motion `disambiguate`):
// - two identical L-shaped rooms, one with a doorway onto a corridor (one wall apart: by default
//   no goal, the base tours; asked for goals that only help): from where the robot
//   stands the door is hidden and the places look alike; the suggested goal is reachable in
//   both and the doorway is in view from it in the room that has it (checked by a ray caster
//   written here, not the guide's);
// - two offices alike inside, off one corridor: the goal is in the corridor, walked to through
//   the door (no straight line gets there), and asked again it is as informative;
// - with one place left, no goal;
// - the scenario key parses, and a misspelling is refused naming the line and the right word;
// - a steered base walks towards the goal it is given.
#include "sgraph_fixtures.hpp"
#include "sim/runner/guided_walk.hpp"
#include "sim/scenario/scenario.hpp"
#include "sim/simulation/simulator.hpp"
#include "sim/world/world.hpp"
#include "test_support.hpp"

#include <bimloc/guide/look_goal.hpp>

#include <gtest/gtest.h>

#include <cmath>
#include <fstream>
#include <optional>

using namespace bimloc;

namespace {

// A wall whose room-side face runs along a -> b (0.2 m thick), grown 0.2 m at both ends so
// that corners close.
void addGuideWall(bim::Storey& s, Eigen::Vector2d a, Eigen::Vector2d b, const Eigen::Vector2d& offset) {
  const Eigen::Vector2d u = (b - a).normalized();
  a += offset - 0.2 * u, b += offset + 0.2 * u;
  s.walls.push_back(test::boxWall("W" + std::to_string(s.walls.size()), a, b, 0.2));
}

// The L-shaped room [0, 6] x [0, 3] + [0, 3] x [3, 8] at `o`; with a doorway x 1.0-1.8 in its
// north wall and a corridor wall 2.5 m beyond it when `door`.
void guideLRoom(bim::Storey& s, const Eigen::Vector2d& o, bool door) {
  addGuideWall(s, {0, 0}, {6, 0}, o);
  addGuideWall(s, {6, 0}, {6, 3}, o);
  addGuideWall(s, {6, 3}, {3, 3}, o);
  addGuideWall(s, {3, 3}, {3, 8}, o);
  if (door) {
    addGuideWall(s, {3, 8}, {2, 8}, o), addGuideWall(s, {0.8, 8}, {0, 8}, o);
    addGuideWall(s, {-2, 10.5}, {5, 10.5}, o);
  } else {
    addGuideWall(s, {3, 8}, {0, 8}, o);
  }
  addGuideWall(s, {0, 8}, {0, 0}, o);
}

// Whether the segment p -> q crosses no wall face: by each face's plane (p and q on opposite
// sides) and where along the face the crossing falls; not the guide's ray caster.
bool lineOfSight(const bim::Storey& s, const Eigen::Vector2d& p, const Eigen::Vector2d& q) {
  for (const auto& w : s.walls)
    for (const auto& f : w.faces) {
      const double dp = f.plane.signedDistance({p.x(), p.y(), 0.5}), dq = f.plane.signedDistance({q.x(), q.y(), 0.5});
      if ((dp > 0) == (dq > 0)) continue;
      const Eigen::Vector2d x = p + dp / (dp - dq) * (q - p);
      const Eigen::Vector2d along = (f.end - f.start).head<2>();
      const double u = (x - f.start.head<2>()).dot(along) / along.squaredNorm();
      if (u >= 0 && u <= 1) return false;
    }
  return true;
}

bim::Storey twinRooms() {
  bim::Storey s;
  guideLRoom(s, {0, 0}, true);
  guideLRoom(s, {20, 0}, false);
  return s;
}

}  // namespace

TEST(Guide, TheGoalBringsTheDoorThatTellsTwinRoomsApartIntoView) {
  const bim::Storey s = twinRooms();
  // The rooms differ by one wall seen through the doorway: half the filter's bar. By default a
  // goal must be predicted to decide, so there is none (the base tours); asked for goals that
  // only help, the planner finds the one that brings the doorway into view.
  const std::vector<guide::Place> places{{PlanarPose(5.0, 1.5, 0.0), 0.0}, {PlanarPose(25.0, 1.5, 0.0), 2.0}};
  EXPECT_FALSE(guide::GoalPlanner(s, guide::GuideConfig{}).suggest(places, PlanarPose::Zero()).has_value());
  guide::GuideConfig config;
  config.min_information = 0.3;
  const guide::GoalPlanner planner(s, config);
  // The robot at (5, 1.5) facing east: the wall at y = 3 hides the north wall and its doorway.
  ASSERT_FALSE(lineOfSight(s, {5.0, 1.5}, {1.4, 8.0}));
  EXPECT_LT(planner.information({places[0].T_map_base, places[1].T_map_base}), config.min_information);
  const PlanarPose odom(-3.0, 7.0, 0.4);  // any odom frame: the goal is a motion of the base
  const auto goal = planner.suggest(places, odom);
  ASSERT_TRUE(goal.has_value());
  ASSERT_EQ(goal->T_map_goal.size(), 2u);
  const Eigen::Vector2d a = goal->T_map_goal[0].head<2>(), b = goal->T_map_goal[1].head<2>();
  // The same motion in both places, and in the odom frame.
  EXPECT_NEAR((b - a - Eigen::Vector2d(20.0, 0.0)).norm(), 0.0, 1e-9);
  EXPECT_NEAR((compose(odom, goal->motion) - goal->T_odom_goal).norm(), 0.0, 1e-9);
  // In both rooms (round the L's corner: walked there, not in a straight line), clear of the walls.
  EXPECT_TRUE(a.x() > 0.4 && a.x() < 5.6 && a.y() > 0.4 && a.y() < 7.6 && (a.x() < 2.6 || a.y() < 2.6)) << a.transpose();
  EXPECT_TRUE(b.x() > 20.4 && b.x() < 25.6 && b.y() > 0.4 && b.y() < 7.6 && (b.x() < 22.6 || b.y() < 2.6)) << b.transpose();
  EXPECT_GE(goal->walk_m, goal->distance_m - 0.2);
  EXPECT_LE(goal->walk_m, config.goal_walk_max_m);
  // From the goal the doorway is in view in room A, and beyond it the corridor's wall.
  EXPECT_TRUE(lineOfSight(s, a, {1.4, 8.3})) << "goal " << a.transpose();
  EXPECT_NEAR(goal->information, 0.5, 1e-9);  // one wall of the two
  EXPECT_LE(goal->distance_m, config.goal_max_m + 1e-9);
}

// Two offices alike inside, [0, 4] x [0, 4] at x = 0 and x = 6, each with a doorway x 1.4-2.6
// in its north wall onto one corridor y 4.2-6.2 from x = -2 to x = 20: only the corridor's ends
// tell them apart, and they are seen from the corridor, not from inside.
bim::Storey officesOnACorridor() {
  bim::Storey s;
  for (const double x : {0.0, 6.0}) {
    const Eigen::Vector2d o(x, 0.0);
    addGuideWall(s, {0, 0}, {4, 0}, o), addGuideWall(s, {4, 0}, {4, 4}, o), addGuideWall(s, {0, 4}, {0, 0}, o);
    addGuideWall(s, {0, 4}, {1.2, 4}, o), addGuideWall(s, {2.8, 4}, {4, 4}, o);  // grown: a 1.2 m doorway
  }
  addGuideWall(s, {-2, 6.4}, {20, 6.4}, {0, 0});
  addGuideWall(s, {-2, 4.2}, {-2, 6.4}, {0, 0}), addGuideWall(s, {20, 6.4}, {20, 4.2}, {0, 0});
  addGuideWall(s, {4.2, 4.2}, {5.8, 4.2}, {0, 0}), addGuideWall(s, {10.2, 4.2}, {20, 4.2}, {0, 0});
  return s;
}

TEST(Guide, TwinOfficesSendTheRobotThroughItsDoorIntoTheCorridor) {
  const bim::Storey s = officesOnACorridor();
  const guide::GuideConfig config;
  const guide::GoalPlanner planner(s, config);
  // At (1, 1) in either office: inside, the two scans are the same.
  const std::vector<guide::Place> places{{PlanarPose(1.0, 1.0, 0.0), 0.0}, {PlanarPose(7.0, 1.0, 0.0), 2.0}};
  const auto goal = planner.suggest(places, PlanarPose::Zero());
  ASSERT_TRUE(goal.has_value());
  const Eigen::Vector2d a = goal->T_map_goal[0].head<2>(), b = goal->T_map_goal[1].head<2>();
  // In the corridor in both places, reached through the door: no straight line gets there.
  EXPECT_TRUE(a.y() > 4.4 && a.y() < 6.2 && b.y() > 4.4 && b.y() < 6.2) << a.transpose() << " / " << b.transpose();
  EXPECT_FALSE(lineOfSight(s, {1.0, 1.0}, a) && lineOfSight(s, {7.0, 1.0}, b)) << a.transpose();
  EXPECT_GT(goal->walk_m, goal->distance_m);
  EXPECT_GT(goal->information, 0.5);
  // The goal's information, asked again for the same motion, is what the suggestion said.
  const auto again = planner.informationOf(places, goal->motion);
  ASSERT_TRUE(again.has_value());
  EXPECT_NEAR(*again, goal->information, 1e-9);
}

TEST(Guide, OnePlaceLeftNeedsNoGoal) {
  const bim::Storey s = twinRooms();
  const guide::GoalPlanner planner(s, guide::GuideConfig{});
  EXPECT_FALSE(planner.suggest({{PlanarPose(5.0, 1.5, 0.0), 0.0}}, PlanarPose::Zero()).has_value());
  EXPECT_FALSE(planner.suggest({}, PlanarPose::Zero()).has_value());
}

TEST(Guide, PredictedScanMatchesTheRoom) {
  // From (5, 1.5): the room-side faces, 0.1 m inside the walls' axes (x = 6, y = 3, x = 0, y = 0).
  const bim::Storey s = twinRooms();
  guide::GuideConfig config;
  config.scan_rays = 4;
  const auto ranges = guide::GoalPlanner(s, config).predictScan(PlanarPose(5.0, 1.5, 0.0));
  ASSERT_EQ(ranges.size(), 4u);
  EXPECT_NEAR(ranges[0], 0.9, 1e-9);  // east
  EXPECT_NEAR(ranges[1], 1.4, 1e-9);  // north: the wall at y = 3
  EXPECT_NEAR(ranges[2], 4.9, 1e-9);  // west
  EXPECT_NEAR(ranges[3], 1.4, 1e-9);  // south
}

namespace bimloc::sim {
namespace {

std::string guideScenario(const std::string& motion) {
  const std::string path = test::tempDir("guide") + "/disambiguate.yaml";
  std::ofstream(path) << "world: " << BIMLOC_WORLDS_DIR << "/site_office.ifc\nstart: {room: R101}\nduration_s: 20\nmotion: " << motion
                      << "\n";
  return path;
}

TEST(GuideScenario, TheMotionTypeParsesAndAMisspellingIsRefused) {
  const Scenario s = loadScenario(guideScenario("{type: disambiguate}"));
  EXPECT_TRUE(s.motion.disambiguate);
  EXPECT_EQ(s.motion.kind, MotionConfig::Kind::Tour);
  EXPECT_TRUE(s.motion.explore_after_tour);
  const Scenario with_rooms = loadScenario(guideScenario("{type: disambiguate, rooms: [R102]}"));
  EXPECT_EQ(with_rooms.motion.rooms, std::vector<std::string>{"R102"});
  const std::string bad = guideScenario("{type: disambigaute}");
  try {
    loadScenario(bad);
    ADD_FAILURE() << "a misspelled motion type was accepted";
  } catch (const ScenarioError& e) {
    const std::string message = e.what();
    EXPECT_EQ(message.rfind(bad + ":4: ", 0), 0u) << message;
    EXPECT_NE(message.find("did you mean 'disambiguate'"), std::string::npos) << message;
  }
}

TEST(GuideScenario, TheSteeredBaseWalksTowardsTheGoal) {
  const Scenario s = loadScenario(guideScenario("{type: disambiguate}"));
  const World world = World::fromPlan(s.world);
  const Simulator sim(s, world);
  GuidedWalk walk(sim);
  const Eigen::Isometry3d start = walk.T_map_base(0.0);
  // The odom frame where the base starts, turned: the goal 2 m ahead of the base in odom.
  const Eigen::Isometry3d T_odom_base = Eigen::Translation3d(1.0, 2.0, 0.0) * Eigen::AngleAxisd(0.8, Eigen::Vector3d::UnitZ());
  guide::LookGoal goal;
  const PlanarPose odom = planarPose(T_odom_base);
  // Towards the middle of the start room, whichever way the base faces.
  const PlanarPose T_world_odom = compose(planarPose(start), inverse(odom));
  // Halfway to a corner of the start room (the base may start at its very centre).
  const Eigen::Vector2d corner = world.building().storeys[sim.storey()].findRoom("R101")->footprint.front();
  const Eigen::Vector2d here = start.translation().head<2>();
  const Eigen::Vector2d target = here + std::min(1.5, 0.5 * (corner - here).norm()) * (corner - here).normalized();
  ASSERT_GT((target - here).norm(), 0.5);
  goal.T_odom_goal = compose(inverse(T_world_odom), PlanarPose(target.x(), target.y(), 0.0));
  walk.follow(LocalizationState::Searching, goal, T_odom_base, start, 0.1);
  ASSERT_EQ(walk.goalsTaken(), 1);
  ASSERT_TRUE(walk.goal().has_value());
  EXPECT_NEAR((*walk.goal() - target).norm(), 0.0, 1e-6);
  const Eigen::Vector2d later = walk.T_map_base(15.0).translation().head<2>();
  EXPECT_LT((later - target).norm(), 0.3) << "at " << later.transpose() << ", goal " << target.transpose();
  EXPECT_LT((later - target).norm(), (here - target).norm());
}

}  // namespace
}  // namespace bimloc::sim
