// Apartment blocks and stacked storeys (sim/worldgen/random_apartment_block.cpp,
// random_storeys.hpp, ifc4_stairs.hpp): the two flats are mirror images about the core (judged
// from the spec's walls, doorways and rooms, spec_symmetry.hpp), a building of N storeys has
// the stairs in the STEP text with the numbers the spec has (read back from the text, not from
// the writer), the real extraction of every storey gives the spec's rooms and walls - the
// stairs and landings add none - and the same seed gives the same bytes.
#include "plan_checks.hpp"
#include "spec_compare.hpp"
#include "test_support.hpp"

#include "sim/base/free_space.hpp"
#include "sim/base/motion_config.hpp"
#include "sim/worldgen/ifc4_writer.hpp"
#include "sim/worldgen/random_world.hpp"
#include "sim/worldgen/spec_check.hpp"
#include "sim/worldgen/spec_symmetry.hpp"

#include <bimloc/bim/ifc_reader.hpp>

#include <gtest/gtest.h>

#include <cmath>
#include <fstream>
#include <map>
#include <regex>
#include <set>
#include <sstream>

using namespace bimloc;

namespace {

constexpr std::uint64_t kFirstBlockSeed = 96000, kBlockSeeds = 12;

worldgen::RandomWorldOptions block(int storeys = 1, worldgen::RandomStyle style = worldgen::RandomStyle::ApartmentBlock) {
  worldgen::RandomWorldOptions o;
  o.style = style;
  o.storeys = storeys;
  return o;
}

// A STEP entity instance: its type and its top-level arguments, as text.
struct StepEntity {
  std::string type;
  std::vector<std::string> args;
};

// The DATA section's instances by id. Splits on top-level commas only (lists stay whole);
// the writer's strings hold no commas or parentheses that matter here.
std::map<int, StepEntity> parseStep(const std::string& text) {
  std::map<int, StepEntity> out;
  static const std::regex line(R"(^#(\d+)=([A-Z0-9]+)\((.*)\);$)");
  std::istringstream in(text);
  std::string l;
  while (std::getline(in, l)) {
    std::smatch m;
    if (!std::regex_match(l, m, line)) continue;
    StepEntity e{m[2], {}};
    const std::string body = m[3];
    int depth = 0;
    bool quoted = false;
    std::string arg;
    for (char c : body) {
      if (c == '\'') quoted = !quoted;
      if (!quoted && c == '(') ++depth;
      if (!quoted && c == ')') --depth;
      if (!quoted && depth == 0 && c == ',') {
        e.args.push_back(arg), arg.clear();
      } else {
        arg += c;
      }
    }
    e.args.push_back(arg);
    out[std::stoi(m[1])] = e;
  }
  return out;
}

std::vector<int> refList(const std::string& list) {
  std::vector<int> out;
  static const std::regex id(R"(#(\d+))");
  for (auto it = std::sregex_iterator(list.begin(), list.end(), id); it != std::sregex_iterator(); ++it)
    out.push_back(std::stoi((*it)[1]));
  return out;
}

int refOf(const std::string& arg) { return arg.size() > 1 && arg[0] == '#' ? std::stoi(arg.substr(1)) : -1; }

std::string quotedName(const worldgen::StairFlightSpec& f) { return "'" + f.name + "'"; }

}  // namespace

// Every block: a lobby and a stairwell between two flats whose walls, doorways and rooms are
// mirror images about the core's axis but for the one small change (or the core's doors).
TEST(ApartmentBlock, TheFlatsAreMirrorImagesAboutTheStairCore) {
  int near_symmetric = 0;
  for (std::uint64_t seed = kFirstBlockSeed; seed < kFirstBlockSeed + kBlockSeeds; ++seed) {
    worldgen::RandomWorldInfo info;
    const auto spec = worldgen::randomWorld(seed, block(), &info);
    const auto& s = spec.storeys.at(0);
    const std::string at = spec.name;
    EXPECT_EQ(spec.name, "random_apartment_block_" + std::to_string(seed));
    EXPECT_NO_THROW(worldgen::checkWorldSpec(spec)) << at;
    std::map<std::string, int> uses;
    for (const auto& r : s.rooms) ++uses[r.long_name];
    EXPECT_EQ(uses["Lobby"], 1) << at;
    EXPECT_EQ(uses["Stairwell"], 1) << at;
    for (const char* use : {"Hall", "Living room", "Kitchen", "Bathroom"}) EXPECT_EQ(uses[use], 2) << at << " " << use;
    EXPECT_TRUE(uses["Bedroom"] == 2 || uses["Bedroom"] == 4) << at;
    EXPECT_TRUE(s.stairs.empty() && s.floor_openings.empty()) << at << ": one storey has no stair";

    // Mirror x (about the outline's centre, which is the core's axis): a few doorways or walls
    // without a twin, never none; the other two symmetries leave most of the plan unmatched.
    std::map<std::string, int> mismatches;
    for (const auto& m : worldgen::symmetryMismatches(s)) mismatches[m.symmetry] = m.total();
    EXPECT_GE(mismatches["mirror x"], 1) << at << " is exactly symmetric";
    EXPECT_LE(mismatches["mirror x"], 6) << at;
    EXPECT_GE(mismatches["mirror y"], 10) << at;
    EXPECT_EQ(info.closest_symmetry, "mirror x") << at;

    // The rooms: every room west of the axis has its mirror image east of it (same use, the
    // footprint's bounding box mirrored within 1 cm), but for the room(s) the change touched.
    double x_lo = 1e9, x_hi = -1e9;
    for (const auto& p : s.outline) x_lo = std::min(x_lo, p.x()), x_hi = std::max(x_hi, p.x());
    const double axis = (x_lo + x_hi) / 2;
    const auto box = [](const worldgen::RoomSpec& r) {
      Eigen::Vector4d b(1e9, 1e9, -1e9, -1e9);
      for (const auto& p : r.footprint) b = Eigen::Vector4d(std::min(b[0], p.x()), std::min(b[1], p.y()), std::max(b[2], p.x()), std::max(b[3], p.y()));
      return b;
    };
    int west = 0, twinned = 0;
    for (const auto& r : s.rooms) {
      const auto b = box(r);
      if (b[2] > axis) continue;  // not wholly west
      ++west;
      for (const auto& q : s.rooms) {
        const auto c = box(q);
        if (q.long_name == r.long_name && std::abs(c[0] - (2 * axis - b[2])) < 0.01 && std::abs(c[2] - (2 * axis - b[0])) < 0.01 &&
            std::abs(c[1] - b[1]) < 0.01 && std::abs(c[3] - b[3]) < 0.01)
          ++twinned;
      }
    }
    EXPECT_GE(west, 5) << at;
    EXPECT_GE(twinned, west - 2) << at << ": the flats are not mirror images";
    if (!info.near_symmetric) {
      EXPECT_EQ(twinned, west) << at;
    }

    // Every room can be walked to from the lobby.
    const auto reached = test::roomsReachedOnFoot(s, 0, sim::MotionConfig{}.body_radius_m + sim::FreeSpace::kMargin_m);
    for (std::size_t r = 0; r < s.rooms.size(); ++r) EXPECT_TRUE(reached[r]) << at << ": " << s.rooms[r].name;
    near_symmetric += info.near_symmetric;
  }
  EXPECT_GE(near_symmetric, 3) << "about half the blocks are changed in one small place";
  EXPECT_LE(near_symmetric, 9);
}

// N storeys: the stair from each storey to the next in the STEP text - IfcStair aggregating two
// IfcStairFlights and a landing IfcSlab, contained in its storey - with the spec's numbers, and
// the floor slab above voided where the flights rise through it.
TEST(ApartmentBlock, StoreysAreJoinedByStairsWrittenAsTheSpecSays) {
  for (const auto& [style, storeys] : {std::pair{worldgen::RandomStyle::ApartmentBlock, 3},
                                       std::pair{worldgen::RandomStyle::ApartmentBlock, 5},
                                       std::pair{worldgen::RandomStyle::Office, 2}}) {
    const auto spec = worldgen::randomWorld(kFirstBlockSeed, block(storeys, style));
    const std::string at = spec.name;
    ASSERT_EQ(spec.storeys.size(), static_cast<std::size_t>(storeys)) << at;
    const auto step = parseStep(worldgen::writeIfc4(spec));
    std::map<std::string, std::vector<int>> by_type;
    for (const auto& [id, e] : step) by_type[e.type].push_back(id);
    EXPECT_EQ(by_type["IFCBUILDINGSTOREY"].size(), static_cast<std::size_t>(storeys)) << at;
    ASSERT_EQ(by_type["IFCSTAIR"].size(), static_cast<std::size_t>(storeys - 1)) << at;
    ASSERT_EQ(by_type["IFCSTAIRFLIGHT"].size(), 2u * (storeys - 1)) << at;

    // Each flight's attributes (IFC4: ..., Tag, NumberOfRisers, NumberOfTreads, RiserHeight,
    // TreadLength, PredefinedType) against the spec's flight of that name.
    std::map<std::string, const worldgen::StairFlightSpec*> flights;
    for (std::size_t k = 0; k + 1 < spec.storeys.size(); ++k) {
      ASSERT_EQ(spec.storeys[k].stairs.size(), 1u) << at;
      const auto& stair = spec.storeys[k].stairs[0];
      double rise = 0.0;
      for (const auto& f : stair.flights) flights[quotedName(f)] = &f, rise += f.rise_m();
      EXPECT_NEAR(rise, spec.storeys[k].height_m, 1e-9) << at;
      EXPECT_NEAR(spec.storeys[k + 1].elevation_m - spec.storeys[k].elevation_m, spec.storeys[k].height_m, 1e-9) << at;
    }
    EXPECT_TRUE(spec.storeys.back().stairs.empty()) << at;
    for (int id : by_type["IFCSTAIRFLIGHT"]) {
      const auto& a = step.at(id).args;
      ASSERT_EQ(a.size(), 13u) << at;
      ASSERT_TRUE(flights.count(a[2])) << at << " " << a[2];
      const auto& f = *flights.at(a[2]);
      EXPECT_EQ(std::stoi(a[8]), f.risers) << at;
      EXPECT_EQ(std::stoi(a[9]), f.risers - 1) << at;
      EXPECT_NEAR(std::stod(a[10]), f.riser_m, 1e-9) << at;
      EXPECT_NEAR(std::stod(a[11]), f.going_m, 1e-9) << at;
      EXPECT_EQ(a[12], ".STRAIGHT.") << at;
      EXPECT_LE(f.riser_m, 0.185 + 1e-9) << at;
      EXPECT_NEAR(2 * f.riser_m + f.going_m, 0.63, 0.03) << at;  // the step rule
      EXPECT_GE(f.width_m, 0.9) << at;
      EXPECT_NE(step.at(refOf(a[6])).type, "") << at;  // a representation
    }
    // Each stair: no body, .HALF_TURN_STAIR., aggregating its two flights and one landing, and
    // contained in a storey.
    std::set<int> contained;
    for (int id : by_type["IFCRELCONTAINEDINSPATIALSTRUCTURE"])
      for (int e : refList(step.at(id).args[4])) contained.insert(e);
    int landings = 0;
    for (int id : by_type["IFCSLAB"]) landings += step.at(id).args[8] == ".LANDING.";
    EXPECT_EQ(landings, storeys - 1) << at;
    for (int stair : by_type["IFCSTAIR"]) {
      EXPECT_EQ(step.at(stair).args[6], "$") << at;
      EXPECT_EQ(step.at(stair).args[8], ".HALF_TURN_STAIR.") << at;
      EXPECT_TRUE(contained.count(stair)) << at;
      int parts_found = 0;
      for (int rel : by_type["IFCRELAGGREGATES"]) {
        if (refOf(step.at(rel).args[4]) != stair) continue;
        std::multiset<std::string> parts;
        for (int p : refList(step.at(rel).args[5])) {
          parts.insert(step.at(p).type == "IFCSLAB" ? step.at(p).args[8] : step.at(p).type);
          EXPECT_FALSE(contained.count(p)) << at << ": a part is in the storey itself";
        }
        EXPECT_EQ(parts, (std::multiset<std::string>{".LANDING.", "IFCSTAIRFLIGHT", "IFCSTAIRFLIGHT"})) << at;
        ++parts_found;
      }
      EXPECT_EQ(parts_found, 1) << at;
    }
    // The voids: one opening in each floor slab above the ground floor, and it covers the
    // flights of the storey below (their plan rectangles lie inside it).
    int slab_voids = 0;
    for (int id : by_type["IFCRELVOIDSELEMENT"]) {
      const auto& voided = step.at(refOf(step.at(id).args[4]));
      if (voided.type != "IFCSLAB") continue;
      EXPECT_EQ(voided.args[8], ".FLOOR.") << at;
      EXPECT_EQ(step.at(refOf(step.at(id).args[5])).type, "IFCOPENINGELEMENT") << at;
      ++slab_voids;
    }
    EXPECT_EQ(slab_voids, storeys - 1) << at;
    for (std::size_t k = 1; k < spec.storeys.size(); ++k) {
      ASSERT_EQ(spec.storeys[k].floor_openings.size(), 1u) << at;
      Eigen::Vector2d lo(1e9, 1e9), hi(-1e9, -1e9);
      for (const auto& p : spec.storeys[k].floor_openings[0]) lo = lo.cwiseMin(p), hi = hi.cwiseMax(p);
      for (const auto& f : spec.storeys[k - 1].stairs[0].flights) {
        const Eigen::Vector2d side(-f.direction.y(), f.direction.x());
        for (double u : {0.0, f.run_m()})
          for (double v : {-f.width_m / 2, f.width_m / 2}) {
            const Eigen::Vector2d p = f.start + f.direction * u + side * v;
            EXPECT_TRUE(p.x() > lo.x() - 1e-9 && p.x() < hi.x() + 1e-9 && p.y() > lo.y() - 1e-9 && p.y() < hi.y() + 1e-9)
                << at << ": " << f.name << " is not under the void";
          }
      }
    }
  }
}

// The real extraction of every storey gives the spec's storeys, walls (the stairs and landings
// make none) and rooms.
TEST(ApartmentBlock, ExtractionOfEveryStoreyGivesTheSpecsRoomsAndWalls) {
  const std::string dir = test::tempDir("apartment_blocks");
  test::SpecTolerance tolerance;
  tolerance.thickness_m = tolerance.axis_m = tolerance.face_m = tolerance.vertex_m = 1e-4;
  tolerance.area_m2 = 1e-3;
  for (const auto& [style, storeys] : {std::pair{worldgen::RandomStyle::ApartmentBlock, 1},
                                       std::pair{worldgen::RandomStyle::ApartmentBlock, 3},
                                       std::pair{worldgen::RandomStyle::Office, 2}}) {
    const auto spec = worldgen::randomWorld(kFirstBlockSeed + 1, block(storeys, style));
    const std::string path = dir + "/" + spec.name + ".ifc";
    std::ofstream(path) << worldgen::writeIfc4(spec);
    const bim::Building building = bim::readIfc(path);
    test::expectStoreysMatch(spec, building);
    test::expectWallsMatch(spec, building, tolerance);
    test::expectRoomsMatch(spec, building, tolerance);
    for (std::size_t k = 0; k < building.storeys.size(); ++k) {
      EXPECT_EQ(building.storeys[k].walls.size(), spec.storeys[k].walls.size()) << spec.name << " storey " << k;
      // The flights' bodies as the reader meshed them: each spans its plan rectangle (run x
      // width) and rises from its floor to its last tread.
      int flights = 0;
      const auto& storey = building.storeys[k];
      for (const auto& part : storey.mesh_parts) {
        if (part.ifc_class != "IfcStairFlight") continue;
        ++flights;
        const worldgen::StairFlightSpec* f = nullptr;
        for (const auto& stair : spec.storeys[k].stairs)
          for (const auto& candidate : stair.flights) f = candidate.name == part.name ? &candidate : f;
        ASSERT_NE(f, nullptr) << spec.name << ": " << part.name;
        Eigen::Vector3d lo = Eigen::Vector3d::Constant(1e9), hi = -lo;
        for (std::uint32_t v = part.first_vertex; v < part.first_vertex + part.vertex_count; ++v) {
          const Eigen::Vector3d p = storey.mesh.vertices[v].cast<double>();
          lo = lo.cwiseMin(p), hi = hi.cwiseMax(p);
        }
        const Eigen::Vector2d side(-f->direction.y(), f->direction.x());
        const Eigen::Vector2d a = f->start - side * f->width_m / 2, b = f->start + f->direction * f->run_m() + side * f->width_m / 2;
        EXPECT_NEAR(lo.x(), std::min(a.x(), b.x()), 1e-3) << part.name;
        EXPECT_NEAR(hi.x(), std::max(a.x(), b.x()), 1e-3) << part.name;
        EXPECT_NEAR(lo.y(), std::min(a.y(), b.y()), 1e-3) << part.name;
        EXPECT_NEAR(hi.y(), std::max(a.y(), b.y()), 1e-3) << part.name;
        EXPECT_NEAR(lo.z(), spec.storeys[k].elevation_m + f->z_m, 1e-3) << part.name;
        EXPECT_NEAR(hi.z(), spec.storeys[k].elevation_m + f->z_m + f->treads() * f->riser_m, 1e-3) << part.name;
      }
      EXPECT_EQ(flights, k + 1 < building.storeys.size() ? 2 : 0) << spec.name << " storey " << k << ": flights in the mesh";
    }
  }
}

TEST(ApartmentBlock, TheSameSeedGivesTheSameBytes) {
  std::set<std::string> texts;
  for (int storeys : {1, 3})
    for (std::uint64_t seed = kFirstBlockSeed; seed < kFirstBlockSeed + 3; ++seed) {
      const std::string text = worldgen::writeIfc4(worldgen::randomWorld(seed, block(storeys)));
      EXPECT_EQ(worldgen::writeIfc4(worldgen::randomWorld(seed, block(storeys))), text) << seed;
      texts.insert(text);
    }
  EXPECT_EQ(texts.size(), 6u);
  // The ground floor of a stacked building is the single floor of the same seed (but for the
  // walls' height, up to the slab above rather than to the roof).
  const auto one = worldgen::randomWorld(kFirstBlockSeed, block(1));
  const auto three = worldgen::randomWorld(kFirstBlockSeed, block(3));
  ASSERT_EQ(one.storeys[0].walls.size(), three.storeys[0].walls.size());
  for (std::size_t k = 0; k < one.storeys[0].walls.size(); ++k) {
    EXPECT_EQ(one.storeys[0].walls[k].name, three.storeys[0].walls[k].name);
    EXPECT_EQ(one.storeys[0].walls[k].start, three.storeys[0].walls[k].start);
    EXPECT_EQ(one.storeys[0].walls[k].end, three.storeys[0].walls[k].end);
  }
  EXPECT_EQ(three.storeys[2].rooms.size(), three.storeys[0].rooms.size());
  EXPECT_EQ(three.storeys[2].doors.size() + 1, three.storeys[0].doors.size()) << "the street door on the ground floor only";
  EXPECT_THROW(worldgen::randomWorld(1, {worldgen::RandomStyle::School, 0, 2}), std::invalid_argument);
  EXPECT_THROW(worldgen::randomWorld(1, block(6)), std::invalid_argument);
}

TEST(ApartmentBlock, CommandLineWritesTheGeneratorsBytes) {
  const std::string dir = test::tempDir("worldgen_blocks");
  auto r = test::runBimloc("worldgen --random 96002 --style apartment_block --storeys 3 --out '" + dir + "/'");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  std::ifstream in(dir + "/random_apartment_block_96002_3storeys.ifc");
  std::stringstream text;
  text << in.rdbuf();
  EXPECT_EQ(text.str(), worldgen::writeIfc4(worldgen::randomWorld(96002, block(3))));
  EXPECT_NE(r.out.find("2 stairs (4 flights)"), std::string::npos) << r.out;
  r = test::runBimloc("worldgen --random 1 --style school --storeys 2 --out '" + dir + "/'");
  EXPECT_NE(r.exit_code, 0);
  EXPECT_NE(r.err.find("office or apartment_block"), std::string::npos) << r.err;
  r = test::runBimloc("worldgen --random 1 --style office --storeys 6 --out '" + dir + "/'");
  EXPECT_NE(r.exit_code, 0);
}
