// Random floors (sim/worldgen/random_world.hpp), 12 seeds of each style: valid specs, the same
// bytes from the same seed, the extraction gives back exactly the generator's walls and rooms,
// every room with a door can be walked to, and the styles have the hard features they promise
// - all judged from the spec's geometry (tests/plan_checks.hpp), not from what the generator says.
#include "plan_checks.hpp"
#include "spec_compare.hpp"
#include "test_support.hpp"

#include "sim/base/free_space.hpp"
#include "sim/base/motion_config.hpp"
#include "sim/world/world.hpp"
#include "sim/worldgen/ifc4_writer.hpp"
#include "sim/worldgen/random_world.hpp"
#include "sim/worldgen/spec_check.hpp"

#include <bimloc/bim/geometry2d.hpp>
#include <bimloc/bim/ifc_reader.hpp>

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <fstream>
#include <set>
#include <sstream>

using namespace bimloc;

namespace {

constexpr std::uint64_t kSeeds = 12;

struct Case {
  std::uint64_t seed;
  worldgen::RandomStyle style;
  worldgen::WorldSpec spec;
  worldgen::RandomWorldInfo info;
  std::string text;
  const worldgen::StoreySpec& storey() const { return spec.storeys.at(0); }
};

const std::vector<Case>& cases() {
  static const std::vector<Case> all = [] {
    std::vector<Case> out;
    for (int style = 0; style < 4; ++style)
      for (std::uint64_t seed = 1; seed <= kSeeds; ++seed) {
        Case c{seed, static_cast<worldgen::RandomStyle>(style), {}, {}, {}};
        c.spec = worldgen::randomWorld(seed, {c.style, 0}, &c.info);
        c.text = worldgen::writeIfc4(c.spec);
        out.push_back(std::move(c));
      }
    return out;
  }();
  return all;
}

// A multiple of 5 mm, as drawings give them.
bool onGrid(double metres) { return std::abs(metres * 200 - std::round(metres * 200)) < 1e-6; }

double bodyRadius() { return sim::MotionConfig{}.body_radius_m + sim::FreeSpace::kMargin_m; }

std::string readFile(const std::string& path) {
  std::ifstream in(path);
  std::stringstream ss;
  ss << in.rdbuf();
  return ss.str();
}

}  // namespace

TEST(RandomWorlds, SpecsAreValidAndTheSameSeedGivesTheSameBytes) {
  std::set<std::string> texts;
  int with_boundaries = 0;
  for (const Case& c : cases()) {
    EXPECT_NO_THROW(worldgen::checkWorldSpec(c.spec)) << c.spec.name;
    EXPECT_EQ(c.spec.name, "random_" + worldgen::randomStyleName(c.style) + "_" + std::to_string(c.seed));
    EXPECT_EQ(worldgen::writeIfc4(worldgen::randomWorld(c.seed, {c.style, 0})), c.text) << c.spec.name;
    texts.insert(c.text);
    with_boundaries += c.spec.space_boundaries ? 1 : 0;
  }
  EXPECT_EQ(texts.size(), cases().size()) << "two seeds gave the same file";
  EXPECT_GT(with_boundaries, 0);
  EXPECT_LT(with_boundaries, static_cast<int>(cases().size()));
  EXPECT_THROW(worldgen::randomStyle("castle"), std::invalid_argument);
}

TEST(RandomWorlds, DimensionsAreWhatArchitectsDraw) {
  const std::set<std::string> plain_rooms = {"Office", "Classroom", "Group room", "Bedroom", "Living room",
                                             "Kitchen", "Bathroom", "Changing room"};
  for (const Case& c : cases()) {
    const auto& s = c.storey();
    const std::string at = c.spec.name;
    EXPECT_GE(s.height_m, 2.8 - 1e-9) << at;
    EXPECT_LE(s.height_m, 3.5 + 1e-9) << at;
    std::set<int> bounding;
    for (const auto& r : s.rooms) bounding.insert(r.walls.begin(), r.walls.end());
    double facade = 0.0;  // the exterior walls' thickness; a wing built onto the facade keeps it inside
    for (const auto& w : s.walls) facade = w.exterior ? w.thickness_m : facade;
    for (std::size_t k = 0; k < s.walls.size(); ++k) {
      const auto& w = s.walls[k];
      const bool free_standing = !bounding.count(static_cast<int>(k));
      const double lo = w.exterior ? 0.30 : 0.10;
      const double hi = w.exterior ? 0.45 : free_standing ? 0.20 : std::abs(w.thickness_m - facade) < 1e-9 ? facade : 0.25;
      EXPECT_GE(w.thickness_m, lo - 1e-9) << at << " " << w.name;
      EXPECT_LE(w.thickness_m, hi + 1e-9) << at << " " << w.name;
      for (double v : {w.start.x(), w.start.y(), w.end.x(), w.end.y(), w.thickness_m / 2}) EXPECT_TRUE(onGrid(v)) << at << " " << w.name;
    }
    for (const auto& d : s.doors) {
      EXPECT_TRUE((d.width_m >= 0.8 - 1e-9 && d.width_m <= 1.0 + 1e-9) || (d.width_m >= 1.2 - 1e-9 && d.width_m <= 1.8 + 1e-9))
          << at << " door " << d.width_m;
      EXPECT_GE(d.height_m, 2.0 - 1e-9) << at;
      EXPECT_LE(d.height_m, 2.1 + 1e-9) << at;
      EXPECT_TRUE(onGrid(d.offset_m)) << at;
    }
    for (const auto& r : s.rooms) {
      Eigen::Vector2d lo = r.footprint.front(), hi = lo;
      for (const auto& p : r.footprint) {
        lo = lo.cwiseMin(p), hi = hi.cwiseMax(p);
        EXPECT_TRUE(onGrid(p.x()) && onGrid(p.y())) << at << " " << r.name;
      }
      const double small = (hi - lo).minCoeff(), large = (hi - lo).maxCoeff();
      if (plain_rooms.count(r.long_name)) {
        EXPECT_GE(small, 2.5 - 1e-9) << at << " " << r.name;
        EXPECT_LE(large, 8.0 + 1e-9) << at << " " << r.name;
      }
      if (r.long_name == "Corridor" && bim::simplifyPolygon(r.footprint).size() == 4) {
        EXPECT_GE(small, 1.5 - 1e-9) << at << " " << r.name;
        EXPECT_LE(small, 2.5 + 1e-9) << at << " " << r.name;
      }
    }
  }
}

// The IFC read back with the real extraction: the generator's walls (faces within 0.1 mm) and
// rooms. Float meshes: at 40 m from the origin a float step is 4e-6 m, so 1e-4 m is tight.
TEST(RandomWorlds, ExtractionGivesTheGeneratorsWallsAndRooms) {
  const std::string dir = test::tempDir("random_worlds");
  test::SpecTolerance tolerance;
  tolerance.thickness_m = tolerance.axis_m = tolerance.face_m = tolerance.vertex_m = 1e-4;
  tolerance.area_m2 = 1e-3;
  for (const Case& c : cases()) {
    const std::string path = dir + "/" + c.spec.name + ".ifc";
    std::ofstream(path) << c.text;
    const bim::Building building = bim::readIfc(path);
    test::expectStoreysMatch(c.spec, building);
    test::expectWallsMatch(c.spec, building, tolerance);
    test::expectRoomsMatch(c.spec, building, tolerance);
  }
}

TEST(RandomWorlds, EveryRoomWithADoorCanBeWalkedTo) {
  for (const Case& c : cases()) {
    const auto& s = c.storey();
    std::vector<int> doors(s.rooms.size(), 0);
    for (const auto& [a, b] : test::doorRooms(s))
      for (int r : {a, b})
        if (r >= 0) ++doors[r];
    const auto first = std::find_if(doors.begin(), doors.end(), [](int n) { return n > 0; });
    ASSERT_NE(first, doors.end()) << c.spec.name;
    const auto reached = test::roomsReachedOnFoot(s, static_cast<int>(first - doors.begin()), bodyRadius());
    for (std::size_t r = 0; r < s.rooms.size(); ++r) {
      const std::string& use = s.rooms[r].long_name;
      if (doors[r] > 0) {
        EXPECT_TRUE(reached[r]) << c.spec.name << ": " << s.rooms[r].name << " cannot be reached";
      } else {
        EXPECT_TRUE(use == "Shaft" || use.find("no door") != std::string::npos) << c.spec.name << " " << use;
      }
    }
  }
}

// The simulator's own planner (Bullet sweeps on the extracted storey mesh, door frames and
// all) finds a path from the first room with a door to the farthest one, in every style.
TEST(RandomWorlds, TheSimulatorsPlannerWalksAcrossTheFloor) {
  const std::string dir = test::tempDir("random_worlds_walk");
  for (const Case& c : cases()) {
    if (c.seed != 1) continue;
    const std::string path = dir + "/" + c.spec.name + ".ifc";
    std::ofstream(path) << c.text;
    const sim::World world = sim::World::fromPlan(path);
    const auto& rooms = world.building().storeys.at(0).rooms;
    std::vector<int> with_door(c.storey().rooms.size(), 0);
    for (const auto& [a, b] : test::doorRooms(c.storey()))
      for (int r : {a, b})
        if (r >= 0) with_door[r] = 1;
    const auto by_name = [&](const std::string& name) {
      return *std::find_if(rooms.begin(), rooms.end(), [&](const bim::Room& r) { return r.name == name; });
    };
    const int from = static_cast<int>(std::find(with_door.begin(), with_door.end(), 1) - with_door.begin());
    const bim::Room& start = by_name(c.storey().rooms[from].name);
    int far = from;
    for (std::size_t r = 0; r < with_door.size(); ++r)
      if (with_door[r] && (by_name(c.storey().rooms[r].name).centre - start.centre).norm() >
                              (by_name(c.storey().rooms[far].name).centre - start.centre).norm())
        far = static_cast<int>(r);
    const bim::Room& goal = by_name(c.storey().rooms[far].name);
    sim::FreeSpace space(world, 0, sim::MotionConfig{}.body_radius_m,
                         sim::bodyCentreZ(world, 0, start.centre, sim::GaitConfig{}.body_height_m));
    const auto a = space.freeSpotNear(start.centre, &start.footprint, 3.0), b = space.freeSpotNear(goal.centre, &goal.footprint, 3.0);
    ASSERT_TRUE(a && b) << c.spec.name;
    EXPECT_FALSE(space.path(*a, *b).empty()) << c.spec.name << ": no path from " << start.name << " to " << goal.name;
  }
}

TEST(RandomWorlds, StylesHaveTheirHardFeatures) {
  int near_symmetric = 0, closed = 0, bent_corridors = 0, l_shaped = 0, t_shaped = 0;
  for (const Case& c : cases()) {
    const auto& s = c.storey();
    const std::string style = worldgen::randomStyleName(c.style), at = c.spec.name;
    if (style == "office" || style == "school") {
      EXPECT_GE(test::longestIdenticalRow(s), 3) << at;
    }
    for (const auto& r : s.rooms) {
      const std::size_t corners = bim::simplifyPolygon(r.footprint).size();
      bent_corridors += r.long_name == "Corridor" && corners > 4;
      closed += r.long_name == "Shaft" || r.long_name.find("no door") != std::string::npos;
    }
    for (const std::string& f : c.info.features) {
      l_shaped += f == "L-shaped corridor";
      t_shaped += f == "T-shaped corridor" || f.rfind("comb:", 0) == 0;
    }
    if (style == "hall") {
      double largest = 0.0;
      for (const auto& r : s.rooms) largest = std::max(largest, std::abs(bim::signedArea(r.footprint)));
      EXPECT_GE(largest, 100.0) << at;
      std::set<int> bounding;
      for (const auto& r : s.rooms) bounding.insert(r.walls.begin(), r.walls.end());
      EXPECT_LT(bounding.size(), s.walls.size()) << at << ": no free-standing wall";
    }
    // Never exactly symmetric; near-symmetric ones differ in a few walls or doorways only.
    const auto counts = test::symmetryCounts(s);
    const int fewest = std::min_element(counts.begin(), counts.end(), [](const auto& a, const auto& b) {
                         return a.unmatched < b.unmatched;
                       })->unmatched;
    EXPECT_GE(fewest, 1) << at << " is symmetric";
    if (c.info.near_symmetric) {
      EXPECT_LE(fewest, 8) << at;
    }
    near_symmetric += fewest <= 8 ? 1 : 0;
  }
  EXPECT_GE(near_symmetric, static_cast<int>(cases().size()) / 3) << "near-symmetric floors should be frequent";
  EXPECT_GT(closed, 0);
  EXPECT_GE(bent_corridors, l_shaped + t_shaped);  // one corridor room around the corner
  EXPECT_GT(l_shaped, 0);
  EXPECT_GT(t_shaped, 0);
}

TEST(RandomWorlds, AHundredRoomsGivesNinetyToHundredAndTen) {
  for (int style = 0; style < 4; ++style) {
    worldgen::RandomWorldOptions options{static_cast<worldgen::RandomStyle>(style), 100};
    const auto spec = worldgen::randomWorld(1, options);
    const std::size_t rooms = spec.storeys.at(0).rooms.size();
    EXPECT_GE(rooms, 90u) << spec.name;
    EXPECT_LE(rooms, 110u) << spec.name;
  }
}

TEST(RandomWorlds, CommandLineWritesTheGeneratorsBytes) {
  const std::string dir = test::tempDir("worldgen_random");
  auto r = test::runBimloc("worldgen --random 7 --style school --out '" + dir + "/'");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_EQ(readFile(dir + "/random_school_7.ifc"),
            worldgen::writeIfc4(worldgen::randomWorld(7, {worldgen::RandomStyle::School, 0})));
  r = test::runBimloc("worldgen --random 3 --random-count 4 --out '" + dir + "/sweep'");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  int lines = 0;
  for (const char* name : {"random_office_3", "random_residential_4", "random_school_5", "random_hall_6"}) {
    EXPECT_NE(r.out.find(std::string(name) + ".ifc"), std::string::npos) << r.out;
    EXPECT_FALSE(readFile(dir + "/sweep/" + name + ".ifc").empty()) << name;
  }
  for (char ch : r.out) lines += ch == '\n';
  EXPECT_EQ(lines, 4) << r.out;
  EXPECT_NE(r.out.find("closest symmetry"), std::string::npos) << r.out;
  r = test::runBimloc("worldgen --random 1 --style castle --out '" + dir + "/'");
  EXPECT_NE(r.exit_code, 0);
  r = test::runBimloc("worldgen site_office --rooms 10 --out '" + dir + "/'");
  EXPECT_NE(r.exit_code, 0);
  EXPECT_NE(r.err.find("--random"), std::string::npos) << r.err;
}
