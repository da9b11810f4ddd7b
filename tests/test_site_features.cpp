// Site worlds, continued: glass passes its fraction of the rays (binomial tolerance), the same
// ray gets the same answer alone or in a packet; a shut door blocks the planner and an open
// one does not; `bimloc simulate` writes the same bytes on 1 and 2 threads with a site and puts
// the truth in metadata.json; bad site input gets FILE:LINE errors and nothing written.
#include "sim/base/free_space.hpp"
#include "sim/scenario/scenario.hpp"
#include "sim/simulation/simulator.hpp"
#include "sim/world/world.hpp"
#include "sim_fixtures.hpp"
#include "test_support.hpp"

#include <bimloc/bim/geometry2d.hpp>

#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <random>
#include <sstream>
#include <tuple>

namespace bimloc::sim {
namespace {

namespace fs = std::filesystem;

const std::string kOffice = std::string(BIMLOC_WORLDS_DIR) + "/site_office.ifc";

TEST(SiteGlass, AWindowPassesItsFractionOfTheRays) {
  BIMLOC_REQUIRE_SHARED(path, "AC20-FZK-Haus.ifc");
  const World plan = World::fromPlan(path);
  const bim::Storey& storey = plan.building().storeys[0];
  const bim::MeshPart* window = nullptr;
  for (const auto& p : storey.mesh_parts)
    if (p.ifc_class == "IfcWindow" && p.triangle_count > 0) window = &p;
  ASSERT_NE(window, nullptr) << "FZK-Haus' ground floor has windows";
  Eigen::Vector3d lo = Eigen::Vector3d::Constant(1e9), hi = -lo;
  for (std::uint32_t v = window->first_vertex; v < window->first_vertex + window->vertex_count; ++v)
    lo = lo.cwiseMin(storey.mesh.vertices[v].cast<double>()), hi = hi.cwiseMax(storey.mesh.vertices[v].cast<double>());
  const Eigen::Vector3d centre = 0.5 * (lo + hi), size = hi - lo;
  // The window's thin horizontal direction is across it: look at it from 1.5 m on either side.
  const Eigen::Vector3d across = size.x() < size.y() ? Eigen::Vector3d::UnitX() : Eigen::Vector3d::UnitY();
  const Eigen::Vector3d along = across.cross(Eigen::Vector3d::UnitZ());
  const double width = std::abs(size.dot(along)), height = size.z();

  SiteConfig c;
  c.preset = "test";
  const double fraction = 0.7;
  c.glass.pass_fraction["IfcWindow"] = fraction;
  const World site = plan.withSite(c, 9);
  ASSERT_EQ(site.siteTruth().glass.size(), 1u);
  EXPECT_GT(site.siteTruth().glass[0].elements, 0u);

  std::mt19937_64 random(1);
  std::uniform_real_distribution<double> unit(-0.3, 0.3);  // the window's middle 60 %
  int on_window = 0, passed = 0;
  for (const double side : {1.0, -1.0}) {
    const Eigen::Vector3f origin = (centre + side * 1.5 * across).cast<float>();
    for (int i = 0; i < 3000; ++i) {
      const Eigen::Vector3d target = centre + unit(random) * width * along + unit(random) * height * Eigen::Vector3d::UnitZ();
      const Eigen::Vector3f dir = (target.cast<float>() - origin).normalized();
      const RayHit before = plan.castRay(0, origin, dir, 0.0f, 20.0f);
      if (!before.hit()) continue;
      const Eigen::Vector3d p = origin.cast<double>() + double(before.range_m) * dir.cast<double>();
      if (((p - lo).array() < -0.01).any() || ((p - hi).array() > 0.01).any()) continue;  // not the window
      ++on_window;
      const RayHit after = site.castRay(0, origin, dir, 0.0f, 20.0f);
      if (!after.hit() || after.range_m > before.range_m + 1e-3) {
        ++passed;
        continue;
      }
      EXPECT_NEAR(after.range_m, before.range_m, 1e-5) << "a ray the glass stops stops where the plan's window is";
      // The same ray in a packet of 16 gets the same answer.
      Eigen::Vector3f origins[16], dirs[16];
      RayHit hits[16];
      for (int k = 0; k < 16; ++k) origins[k] = origin, dirs[k] = dir;
      site.castRays16(0, origins, dirs, 0.0f, 20.0f, hits, 16);
      EXPECT_EQ(hits[7].range_m, after.range_m);
    }
  }
  ASSERT_GT(on_window, 1000) << "too few rays met the window to judge";
  const double rate = double(passed) / on_window, sigma = std::sqrt(fraction * (1 - fraction) / on_window);
  EXPECT_NEAR(rate, fraction, 4.5 * sigma) << passed << " of " << on_window << " rays passed";
}

// The door of an office: its only way out (worldgen's site_office: one door per office).
const DoorTruth& doorOf(const World& world, const bim::Room& room) {
  const DoorTruth* best = nullptr;
  double best_d = 1e9;
  for (const auto& d : world.siteTruth().doors) {
    double dist = 1e9;
    for (std::size_t i = 0; i < room.footprint.size(); ++i) {
      const Eigen::Vector2d a = room.footprint[i], b = room.footprint[(i + 1) % room.footprint.size()];
      const double t = std::clamp((d.centre - a).dot(b - a) / (b - a).squaredNorm(), 0.0, 1.0);
      dist = std::min(dist, (a + t * (b - a) - d.centre).norm());
    }
    if (dist < best_d) best_d = dist, best = &d;
  }
  return *best;
}

TEST(SiteDoors, AShutDoorBlocksThePlannerAnOpenOneDoesNot) {
  const World& plan = test::officeWorld();
  const bim::Storey& storey = plan.building().storeys[0];
  const bim::Room* office = storey.findRoom("R101");
  const bim::Room* corridor = storey.findRoom("C100");
  ASSERT_TRUE(office && corridor);
  const DoorTruth& door = doorOf(plan, *office);
  for (const DoorState state : {DoorState::Open, DoorState::Shut, DoorState::Ajar}) {
    SiteConfig c;
    c.preset = "test";
    c.doors.edits.push_back({door.id, state, 0});
    const World site = plan.withSite(c, 1);
    ASSERT_EQ(site.siteTruth().doors.size(), plan.siteTruth().doors.size());
    const double z = bodyCentreZ(site, 0, office->centre, 0.5);
    FreeSpace space(site, 0, 0.3, z);
    // Spots where the body fits, as the planner's tours take them (the corridor's centre may hold a column).
    const auto from = space.freeSpotNear(office->centre, &office->footprint, 3.0);
    const auto to = space.freeSpotNear(corridor->centre, &corridor->footprint, 3.0);
    ASSERT_TRUE(from && to);
    const auto path = space.path(*from, *to);
    if (state == DoorState::Shut)
      EXPECT_TRUE(path.empty()) << "a shut door let the planner through";
    else
      EXPECT_FALSE(path.empty()) << toString(state) << " door blocked the planner";
  }
}

std::string slurp(const fs::path& p) {
  std::ifstream in(p, std::ios::binary);
  std::stringstream ss;
  ss << in.rdbuf();
  return ss.str();
}

std::string writeScenario(const std::string& dir, const std::string& site_text) {
  const std::string path = dir + "/site.yaml";
  std::ofstream(path) << "world: " << kOffice << "\nstart: {room: R101}\nmotion: {type: tour, rooms: [C100]}\n"
                      << "duration_s: 2\nseed: 4\n" << site_text;
  return path;
}

TEST(SiteSimulate, SameBytesOnOneAndTwoThreadsWithTheTruthInTheMetadata) {
  const std::string dir = test::tempDir("site-simulate");
  // construction (people) with every sensor effect: their draws too are the same on any thread.
  const std::string scenario = writeScenario(
      dir, "site:\n  preset: construction\n  sensor: {glass_dropout: 0.3, dark_fraction: 0.2, dark_dropout: 0.3, "
           "mixed_probability: 0.3}\n");
  ASSERT_EQ(test::runBimloc("simulate '" + scenario + "' --out '" + dir + "/t1' --threads 1 --quiet").exit_code, 0);
  ASSERT_EQ(test::runBimloc("simulate '" + scenario + "' --out '" + dir + "/t2' --threads 2 --quiet").exit_code, 0);
  std::size_t files = 0;
  for (const auto& e : fs::recursive_directory_iterator(dir + "/t1")) {
    if (!e.is_regular_file()) continue;
    const fs::path rel = fs::relative(e.path(), dir + "/t1");
    EXPECT_EQ(slurp(e.path()), slurp(fs::path(dir + "/t2") / rel)) << rel << " differs between 1 and 2 threads";
    ++files;
  }
  EXPECT_GT(files, 10u);
  const auto meta = nlohmann::json::parse(slurp(dir + "/t1/metadata.json"));
  ASSERT_TRUE(meta.contains("site"));
  EXPECT_EQ(meta["site"]["preset"], "construction");
  EXPECT_EQ(meta["site"]["seed"], 4);
  EXPECT_EQ(meta["site"]["people"].size(), 2u) << "construction: 2 people, walking in the scans of both runs alike";
  EXPECT_EQ(meta["site"]["walls"].size(), test::officeWorld().building().storeys[0].walls.size());
}

// A bad site: `bimloc simulate` fails naming FILE:LINE with `part`, and writes nothing.
void expectSimulateError(const std::string& site_text, int line, const std::string& part) {
  const std::string dir = test::tempDir("site-bad");
  const std::string scenario = writeScenario(dir, site_text);
  const auto r = test::runBimloc("simulate '" + scenario + "' --out '" + dir + "/out'");
  EXPECT_NE(r.exit_code, 0) << site_text;
  EXPECT_NE(r.err.find(scenario + ":" + std::to_string(line) + ": "), std::string::npos) << r.err;
  EXPECT_NE(r.err.find(part), std::string::npos) << r.err;
  EXPECT_FALSE(fs::exists(dir + "/out")) << "written despite the error";
}

TEST(SiteSimulate, BadSiteInputGetsFileLineErrorsAndNothingIsWritten) {
  // The head of writeScenario takes 5 lines: site: is line 6.
  expectSimulateError("site: as_bilt\n", 6, "did you mean 'as_built'?");
  expectSimulateError("site: {preset: constuction}\n", 6, "did you mean 'construction'?");
  expectSimulateError("site:\n  walls: {fraction: 1.5}\n", 7, "site.walls.fraction must be in [0, 1]");
  expectSimulateError("site:\n  walls:\n    max_ofset_m: 0.1\n", 8, "did you mean 'max_offset_m'?");
  expectSimulateError("site:\n  walls:\n    partitions: {count: 2.5}\n", 8, "whole number");
  expectSimulateError("site:\n  glass: {IfcWindow: 2}\n", 7, "site.glass.IfcWindow must be in [0, 1]");
  expectSimulateError("site:\n  doors: {shut_fraction: 0.7, ajar_fraction: 0.5}\n", 7, "must not exceed 1");
  expectSimulateError("site:\n  clutter: {density_per_m2: 3}\n", 7, "site.clutter.density_per_m2 must be in [0, 2]");
  expectSimulateError("site:\n  clutter: {min_size_m: [1, 1, 1], max_size_m: [2, 0.5, 2]}\n", 7, "must not exceed max_size_m");
  expectSimulateError("site:\n  cluter: {density_per_m2: 0.1}\n", 7, "did you mean 'clutter'?");
  expectSimulateError("site:\n  doors:\n    edit:\n      - {id: nope, state: shut}\n", 9, "no door 'nope'");
  expectSimulateError("site:\n  doors:\n    edit:\n      - {id: nope, state: shot}\n", 9, "did you mean 'shut'?");
  // A wall id with a typo: the suggestion is the real one.
  const std::string name = test::officeWorld().building().storeys[0].walls[1].name;
  expectSimulateError("site:\n  walls:\n    edit:\n      - {id: " + name + "X, offset_m: 0.1}\n", 9,
                      "no wall '" + name + "X' (GlobalId or name) in the plan (did you mean '" + name + "'?)");
  expectSimulateError("site:\n  walls:\n    edit:\n      - {id: " + name + ", offset_m: 3}\n", 9, "offset_m must be in [-1, 1]");
  // People: a path from R101 straight out through its wall, a key with a typo, a bad probability.
  const Eigen::Vector2d c = test::officeWorld().building().storeys[0].findRoom("R101")->centre;
  const std::string through = "[[" + std::to_string(c.x()) + ", " + std::to_string(c.y()) + "], [" +
                              std::to_string(c.x() + 30.0) + ", " + std::to_string(c.y()) + "]]";
  expectSimulateError("site:\n  people:\n    paths:\n      - {waypoints: " + through + "}\n", 9,
                      "meets a wall at");
  expectSimulateError("site:\n  people:\n    paths:\n      - {waypoints: " + through + "}\n", 9, "move the waypoints");
  expectSimulateError("site:\n  peple: {count: 2}\n", 7, "did you mean 'people'?");
  expectSimulateError("site:\n  people: {count: -1}\n", 7, "site.people.count must be in [0, 100]");
  expectSimulateError("site:\n  sensor: {glass_dropout: 1.5}\n", 7, "site.sensor.glass_dropout must be in [0, 1]");
}

}  // namespace
}  // namespace bimloc::sim

namespace bimloc::sim {
namespace {

// Distance from p to the box (its footprint rectangle), 0 inside.
double distanceToBox(const Eigen::Vector2d& p, const ClutterTruth& c) {
  const double yaw = c.yaw_deg * M_PI / 180.0;
  const Eigen::Vector2d u(std::cos(yaw), std::sin(yaw)), n(-u.y(), u.x());
  const Eigen::Vector2d d = p - c.centre.head<2>();
  const double along = std::max(0.0, std::abs(d.dot(u)) - 0.5 * c.size_m.x());
  const double across = std::max(0.0, std::abs(d.dot(n)) - 0.5 * c.size_m.y());
  return std::hypot(along, across);
}

TEST(SiteTurns, ATurnIsTheSameWhicheverTurnsWereCastBefore) {
  // The loop casts a turn only when a localizer reads its points (run_scenario.cpp); that is
  // the loop that casts every turn only if a turn depends on its index alone: its noise, the
  // site's effects and where the people walk, with nothing carried over from the turns cast
  // before it. The oracle: the same turns from a simulator that cast every turn in order.
  const Scenario s = loadScenario(std::string(BIMLOC_SCENARIOS_DIR) + "/site_office_R101_construction.yaml");
  const World plan = World::load(s.world);
  const Simulator every(s, plan), some(s, plan);
  ASSERT_GT(every.world().siteTruth().people.size(), 0u) << "no people to move between turns";
  const auto bits = [](const LidarPoint& p) {
    return std::make_tuple(p.x, p.y, p.z, p.intensity, p.ring, p.time);
  };
  std::size_t compared = 0;
  for (std::size_t i = 0; i < 40; ++i) {
    const LidarScan all = every.turn(i);
    if (i % 7 != 3) continue;  // the other simulator casts only these
    const LidarScan one = some.turn(i);
    ASSERT_EQ(one.stamp_s, all.stamp_s);
    ASSERT_EQ(one.stamp_s, some.turnStamp(i));
    ASSERT_EQ(one.points.size(), all.points.size()) << "turn " << i;
    for (std::size_t k = 0; k < one.points.size(); ++k) ASSERT_EQ(bits(one.points[k]), bits(all.points[k])) << "turn " << i << " point " << k;
    compared += one.points.size();
  }
  EXPECT_GT(compared, 100000u);
}

TEST(SiteClutter, BoxesStandWhereTheTruthSaysAndTheRobotsPathStaysClear) {
  const Scenario s = loadScenario(std::string(BIMLOC_SCENARIOS_DIR) + "/site_office_R101_construction.yaml");
  const World plan = World::load(s.world);
  const Simulator sim(s, plan);
  const SiteTruth& truth = sim.world().siteTruth();
  ASSERT_GT(truth.clutter.size(), 5u);
  std::size_t free_standing = 0;
  for (const auto& c : truth.clutter) {
    if (c.against_wall) continue;  // its back may stand in a moved wall: look at the free ones
    // A ray at the box's side, 0.5 m out, level with its middle, meets the side (a plan ray does not).
    const double yaw = c.yaw_deg * M_PI / 180.0;
    const Eigen::Vector2d n(-std::sin(yaw), std::cos(yaw));
    const Eigen::Vector2d o2 = c.centre.head<2>() + (0.5 * c.size_m.y() + 0.5) * n;
    const Eigen::Vector3f o(float(o2.x()), float(o2.y()), float(c.centre.z() + 0.5 * c.size_m.z()));
    const Eigen::Vector3f dir(float(-n.x()), float(-n.y()), 0.0f);
    const RayHit hit = sim.world().castRay(0, o, dir, 0.0f, 3.0f);
    ASSERT_TRUE(hit.hit());
    EXPECT_NEAR(hit.range_m, 0.5, 1e-4);
    EXPECT_FALSE(plan.castRay(0, o, dir, 0.0f, 0.55f).hit());
    ++free_standing;
  }
  EXPECT_GT(free_standing, 0u) << "no free-standing box to look at";
  // The body (a circle of body_radius_m) never touches a box, all along the trajectory.
  const double radius = s.motion.body_radius_m;
  double closest = 1e9;
  for (double t = 0.0; t <= s.duration_s; t += 0.05) {
    const Eigen::Vector2d p = sim.trajectory().T_map_base(t).translation().head<2>();
    for (const auto& c : truth.clutter) closest = std::min(closest, distanceToBox(p, c));
  }
  EXPECT_GE(closest, radius);
}

}  // namespace
}  // namespace bimloc::sim
