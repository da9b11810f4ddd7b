// The Duplex (../shared/ifc/Duplex_A_20110907.ifc) converged ~0.4 m off in y toward the
// building's centre. Root cause pinned here: Level 1 has walls hung above the rooms (the stair
// wells' enclosures of Level 2, modelled on Level 1 from 2.61 m up: 2O2Fr$t4X7Zf8NOew3FLTF and
// its twin ...FL8v, 1aj$VJZFn2TxepZUBcKpee and ...phf), which a lidar 0.77 m above the floor
// never sees (the rooms' ceilings are at 2.60 m). From the B101 start, the kitchen counter's
// front (a plane 0.78 m tall at y = -5.81) lies 0.44 m off the hung wall's face (y = -6.25):
// matched to it, the pose 0.37 m south explained the scan as well as the truth. A face is now
// matched only by a plane whose points lie at heights the wall has (pf/landmark.hpp). Second
// cause: the party wall is CMU (...FKRi) with a furring wall (0iEHWY1$XA8eQeeULq4jE6) against
// it; their touching faces are inside the solid, and the pose 0.37 m south put the party
// wall's real face (y = -9.73) onto the buried one at y = -10.22. Faces with another wall's
// body in front of them are no landmarks now (bim/buried_faces.hpp): tested on walls built in
// code (analytic) and on the Duplex.
#include "bim/buried_faces.hpp"
#include "sgraph/association.hpp"
#include "sgraph/plan_layers.hpp"
#include "sgraph/plane_factor.hpp"
#include "sgraph_fixtures.hpp"
#include "sim/runner/room_scenarios.hpp"
#include "sim/simulation/simulator.hpp"
#include "sim/world/world.hpp"
#include "test_support.hpp"

#include <bimloc/geometry/planar_pose.hpp>
#include <bimloc/pf/particle_filter.hpp>
#include <bimloc/planes/plane_extraction.hpp>

#include <gtest/gtest.h>

#include <cmath>

using namespace bimloc;

namespace {

bool buried(const bim::Storey& storey, const std::vector<bool>& b, const std::string& wall, int face) {
  const bim::Wall* w = storey.findWall(wall);
  return w && b.at(static_cast<std::size_t>(2 * (w - storey.walls.data()) + face));
}

}  // namespace

TEST(BuriedFaces, TheFacesWhereTwoWallsTouchAreBuriedNoOtherIs) {
  bim::Storey s;
  // A: y -0.1..0.1; B (furring) against it, y 0.1..0.2; C 1 m away; D covers 1 m of A's 4 m
  // from below; E stands against B's outer face but hangs from 3 m up (above B's top, 2.8 m).
  s.walls.push_back(test::boxWall("A", {0, 0}, {4, 0}, 0.2));
  s.walls.push_back(test::boxWall("B", {0, 0.15}, {4, 0.15}, 0.1));
  s.walls.push_back(test::boxWall("C", {0, 1.2}, {4, 1.2}, 0.2));
  s.walls.push_back(test::boxWall("D", {0, -0.2}, {1, -0.2}, 0.2));
  bim::Wall e = test::boxWall("E", {0, 0.3}, {4, 0.3}, 0.2);
  for (auto* p : {&e.start, &e.end, &e.faces[0].start, &e.faces[0].end, &e.faces[1].start, &e.faces[1].end}) p->z() = 3.0;
  s.walls.push_back(e);
  const std::vector<bool> b = bim::buriedFaces(s);
  EXPECT_TRUE(buried(s, b, "A", 0));   // B's body right in front of it
  EXPECT_TRUE(buried(s, b, "B", 1));   // A's body right in front of it
  EXPECT_FALSE(buried(s, b, "A", 1));  // D covers a quarter of it
  EXPECT_FALSE(buried(s, b, "B", 0));  // E's body is in front of it, but above B's heights
  EXPECT_FALSE(buried(s, b, "C", 0));
  EXPECT_FALSE(buried(s, b, "C", 1));
  EXPECT_TRUE(buried(s, b, "D", 0));   // A's body is in front of all of D's face
  EXPECT_FALSE(buried(s, b, "D", 1));
}

TEST(BuriedFaces, TheSGraphAssociatesNoBuriedFace) {
  // A and its furring B as above; a keyframe north of them. A plane observed exactly where A's
  // buried face is (y = 0.1, as a robot 0.1 m off would see B's real face) matches no face of
  // A's node; B's real face (y = 0.2) still matches B's.
  bim::Storey s;
  s.walls.push_back(test::boxWall("A", {0, 0}, {4, 0}, 0.2));
  s.walls.push_back(test::boxWall("B", {0, 0.15}, {4, 0.15}, 0.1));
  sgraph::detail::Graph g;
  std::vector<std::string> warnings;
  sgraph::detail::buildPlanLayers(s, g, warnings);
  ASSERT_EQ(g.nodes.size(), 2u);
  EXPECT_TRUE(g.nodes[0].buried[0]);
  EXPECT_FALSE(g.nodes[0].buried[1]);
  EXPECT_TRUE(g.nodes[1].buried[1]);
  EXPECT_FALSE(g.nodes[1].buried[0]);
  sgraph::detail::Keyframe kf;
  kf.pose = {2.0, 1.5, 0.3};
  const sgraph::SGraphConfig config;
  // The observation each face would give, exactly: azimuth, elevation, d in the lidar frame.
  const auto exactly = [&](const sgraph::detail::WallNode& node, int k) {
    sgraph::detail::ScanObservation o;
    double minimal[3];
    sgraph::detail::PlaneFactor::predict(node.face[k], kf.A, kf.b, kf.pose.data(), node.params.data(), minimal);
    o.minimal = Eigen::Vector3d(minimal[0], minimal[1], minimal[2]);
    o.covariance = Eigen::Vector3d(1e-4, 1e-4, 1e-4).asDiagonal();
    o.normal_map = node.normal(k);
    o.centroid_map = Eigen::Vector2d(2.0, -node.d(k) / node.normal(k).y());
    o.extent_m = 2.0, o.height_extent_m = 2.0, o.z_map = 1.2;
    o.axis = bim::WallAxis::Y;
    return o;
  };
  EXPECT_FALSE(std::isfinite(sgraph::detail::matchDistance2(g.nodes[0], 0, kf, exactly(g.nodes[0], 0), config)));
  EXPECT_LT(sgraph::detail::matchDistance2(g.nodes[1], 0, kf, exactly(g.nodes[1], 0), config), 1e-6);
}

TEST(DuplexFaces, ACounterAtLidarHeightMatchesNoWallHungAboveTheCeiling) {
  BIMLOC_REQUIRE_SHARED(path, "Duplex_A_20110907.ifc");
  const sim::World world = sim::World::fromPlan(path);
  sim::RoomScenarioOptions o;
  o.plan = path;
  o.storey = "Level 1";
  bool tried = false;
  for (const auto& s : sim::roomScenarios(world, o)) {
    if (s.start.room != "B101") continue;
    const sim::Simulator simu(s, world);
    const bim::Storey& storey = world.building().storeys[simu.storey()];
    // The plan's fact: the hung wall starts above the room's ceiling.
    const bim::Wall* hung = storey.findWall("2O2Fr$t4X7Zf8NOew3FLTF");
    const bim::Room* foyer = storey.findRoom("B101");
    ASSERT_TRUE(hung && foyer);
    EXPECT_GT(hung->faces[1].start.z(), foyer->floor_z + foyer->height_m);
    // The layered party wall: the touching faces are buried, the faces into the rooms are not.
    const std::vector<bool> b = bim::buriedFaces(storey);
    EXPECT_TRUE(buried(storey, b, "2O2Fr$t4X7Zf8NOew3FKRi", 1));
    EXPECT_TRUE(buried(storey, b, "0iEHWY1$XA8eQeeULq4jE6", 0));
    EXPECT_FALSE(buried(storey, b, "2O2Fr$t4X7Zf8NOew3FKRi", 0));
    EXPECT_FALSE(buried(storey, b, "0iEHWY1$XA8eQeeULq4jE6", 1));
    const auto truth = simu.groundTruth();
    // The storey's own elements (this test is about the filter's face heights): the whole
    // building's scan (simu.turn) also holds low planes of elements filed under other storeys,
    // which the storey's plan lacks (docs/results/2026-11-28-session22.md, section 1).
    const auto scan = simu.turnOnItsStoreyAlone(0);
    std::vector<Eigen::Vector3f> points;
    for (const auto& p : scan.points) points.emplace_back(p.x, p.y, p.z);
    const auto walls = planes::extractPlanes(points).walls;
    const Eigen::Isometry3d T_map_base = truth.front().T_map_base;
    const Eigen::Isometry3d T_map_lidar = T_map_base * simu.lidar().config().T_base_lidar;
    // The counter's front: facing -y, under 1.2 m tall, within 0.6 m of the hung wall's face.
    const planes::ObservedPlane* counter = nullptr;
    for (const auto& w : walls) {
      const Eigen::Vector3d n = T_map_lidar.linear() * w.normal, c = T_map_lidar * w.centroid;
      if (n.y() < -0.95 && w.height_extent_m < 1.2 && std::abs(c.y() - hung->faces[1].start.y()) < 0.6) counter = &w;
    }
    ASSERT_NE(counter, nullptr) << "the scan from the B101 start shows no counter front near the hung wall";
    // Every face of the storey (no room factor), base at its true height: at the pose 0.37 m
    // south the counter lies 0.07 m off the hung face; it must still be clutter there.
    pf::ParticleFilterConfig config;
    config.use_rooms = false;
    pf::ParticleFilter filter(storey, simu.lidar().config().T_base_lidar, config);
    Eigen::Isometry3d odom = Eigen::Isometry3d::Identity();
    odom.translation().z() = T_map_base.translation().z() - storey.elevation_m;
    filter.predict(odom);
    const Eigen::Vector3d at = planarPose(T_map_base);
    const auto south = filter.score(at.x(), at.y() - 0.37, at.z(), {*counter});
    EXPECT_EQ(south.second, 0) << "the counter front matched a face at the pose 0.37 m south (log-likelihood " << south.first << ")";
    // The whole scan: the truth explains it better than the pose 0.37 m south.
    EXPECT_GT(filter.score(at.x(), at.y(), at.z(), walls).first, filter.score(at.x(), at.y() - 0.37, at.z(), walls).first);
    tried = true;
  }
  EXPECT_TRUE(tried);
}
