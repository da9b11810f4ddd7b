// The stairs of the shared plans (../shared/ifc) against the plans' own numbers, read by an
// independent oracle: a regex over the STEP text (not IFC++) for the IFCSTAIRFLIGHT attributes,
// the IFCSTAIR lines and the storeys' Elevation. Where a file has only an IfcStair with a body,
// the body-derived numbers are checked against the storey heights and a hand count (below).
// Skips when the folder is absent.
#include "test_support.hpp"

#include <bimloc/bim/ifc_reader.hpp>

#include <gtest/gtest.h>

#include <algorithm>
#include <fstream>
#include <map>
#include <regex>
#include <sstream>

using namespace bimloc::bim;

namespace {

// Revit writes IfcStairFlight's RiserHeight and TreadLength in feet whatever the project's unit
// (the Duplex is in metres, Jesse.1 in millimetres): the type names say so, "200mm Max Riser
// 250mm Tread" for 0.6357 and 0.8202, "180mm max riser 230mm" for 0.5906 and 0.7546.
constexpr double kFootM = 0.3048;

struct OracleFlight {
  int risers = 0, treads = 0;
  double riser_height = 0, tread_length = 0;  // as written in the file
};

struct Oracle {
  std::map<std::string, OracleFlight> flights;  // by GlobalId
  std::size_t stairs = 0;                       // IFCSTAIR lines
  std::vector<double> storey_z_m;               // Elevation × the length unit, sorted
};

Oracle readOracle(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  std::stringstream text;
  text << in.rdbuf();
  const std::string s = text.str();
  Oracle o;
  const double unit = s.find("IFCSIUNIT(*,.LENGTHUNIT.,.MILLI.,.METRE.)") != std::string::npos ? 0.001 : 1.0;
  // IFC2X3 IfcStairFlight: ..., Tag, NumberOfRiser, NumberOfTreads, RiserHeight, TreadLength);
  const std::regex flight(R"(IFCSTAIRFLIGHT\('([^']+)',[^\n]*,(\d+),(\d+),([-0-9.E+]+),([-0-9.E+]+)\);)");
  for (auto it = std::sregex_iterator(s.begin(), s.end(), flight); it != std::sregex_iterator(); ++it)
    o.flights[(*it)[1]] = {std::stoi((*it)[2]), std::stoi((*it)[3]), std::stod((*it)[4]), std::stod((*it)[5])};
  const std::regex stair(R"(=\s*IFCSTAIR\()");
  o.stairs = static_cast<std::size_t>(std::distance(std::sregex_iterator(s.begin(), s.end(), stair), std::sregex_iterator()));
  const std::regex storey(R"(IFCBUILDINGSTOREY\([^\n]*,([-0-9.E+]+)\);)");
  for (auto it = std::sregex_iterator(s.begin(), s.end(), storey); it != std::sregex_iterator(); ++it)
    o.storey_z_m.push_back(std::stod((*it)[1]) * unit);
  std::sort(o.storey_z_m.begin(), o.storey_z_m.end());
  return o;
}

const Building& plan(const std::string& path) {
  static std::map<std::string, Building> cache;
  auto it = cache.find(path);
  if (it == cache.end()) it = cache.emplace(path, readIfc(path)).first;
  return it->second;
}

// A flight's rise against the storeys it links, by the oracle's elevations.
void expectRiseLinksStoreys(const StairFlight& f, const Oracle& o, double tolerance_m) {
  ASSERT_GE(f.bottom_storey, 0) << f.id;
  ASSERT_GE(f.top_storey, 0) << f.id;
  ASSERT_LT(static_cast<std::size_t>(f.top_storey), o.storey_z_m.size());
  EXPECT_NEAR(f.rise_m(), o.storey_z_m[static_cast<std::size_t>(f.top_storey)] - o.storey_z_m[static_cast<std::size_t>(f.bottom_storey)],
              tolerance_m)
      << f.id;
  EXPECT_NEAR(f.run_m(), f.going_m * (f.risers - 1), 0.02) << f.id;  // a straight flight
}

void expectRevitFlights(const char* file, std::size_t flights) {
  BIMLOC_REQUIRE_SHARED(path, file);
  const Oracle o = readOracle(path);
  const Building& b = plan(path);
  ASSERT_EQ(o.flights.size(), flights);
  ASSERT_EQ(b.stairs.size(), o.flights.size());
  for (const auto& f : b.stairs) {
    SCOPED_TRACE(f.id);
    const auto it = o.flights.find(f.id);
    ASSERT_NE(it, o.flights.end());
    const OracleFlight& want = it->second;
    EXPECT_EQ(f.ifc_type, "IfcStairFlight");
    EXPECT_EQ(f.risers, want.risers);
    EXPECT_EQ(want.treads, want.risers - 1);  // the file's own consistency: one tread fewer
    EXPECT_NEAR(f.riser_height_m, want.riser_height * kFootM, 1e-3);
    EXPECT_NEAR(f.going_m, want.tread_length * kFootM, 2e-3);
    EXPECT_EQ(f.source, "attributes+body");  // the counts from the file, the lengths (feet) from the body
    expectRiseLinksStoreys(f, o, 0.01);
  }
}

}  // namespace

// Two mirrored flats, one straight flight each: Level 1 (0 m) to Level 2 (3.1 m), 16 risers.
TEST(SharedStairs, DuplexFlightsAsTheFileStatesThem) {
  expectRevitFlights("Duplex_A_20110907.ifc", 2);
  BIMLOC_REQUIRE_SHARED(path, "Duplex_A_20110907.ifc");
  for (const auto& f : plan(path).stairs) EXPECT_EQ(f.top_storey - f.bottom_storey, 1);
}

// Five flights in five IfcStair: 7 risers (Level -1 to level 0, twice), 10 (level 0 to Level 1,
// twice), 8 (Level 1 to Level 2): each ends on a storey of the file, skipping the "T.O." levels.
TEST(SharedStairs, Jesse1FlightsAsTheFileStatesThem) {
  expectRevitFlights("Jesse.1.ifc", 5);
  BIMLOC_REQUIRE_SHARED(path, "Jesse.1.ifc");
  const Building& b = plan(path);
  std::map<std::string, int> by_storeys;
  for (const auto& f : b.stairs)
    ++by_storeys[b.storeys[static_cast<std::size_t>(f.bottom_storey)].name + " -> " +
                 b.storeys[static_cast<std::size_t>(f.top_storey)].name];
  EXPECT_EQ(by_storeys, (std::map<std::string, int>{
                            {"Level -1 -> level 0", 2}, {"level 0 -> Level 1", 2}, {"Level 1 -> Level 2", 1}}));
}

// Two IfcStair with bodies, no flights: cellar to ground floor and ground floor to attic, each
// 2.9 m. Hand count from the bodies' tread faces (each step a board 0.06 m over its carriage):
// 15 risers of 0.1933 m.
TEST(SharedStairs, JasminSunStairsFromTheirBodies) {
  BIMLOC_REQUIRE_SHARED(path, "AC90R1-Jasmin-Sun-105-2x3.ifc");
  const Oracle o = readOracle(path);
  const Building& b = plan(path);
  EXPECT_TRUE(o.flights.empty());
  ASSERT_EQ(b.stairs.size(), o.stairs);
  ASSERT_EQ(b.stairs.size(), 2u);
  for (const auto& f : b.stairs) {
    SCOPED_TRACE(f.id);
    EXPECT_EQ(f.ifc_type, "IfcStair");
    EXPECT_EQ(f.stair_id, f.id);
    EXPECT_EQ(f.source, "body");
    EXPECT_EQ(f.risers, 15);
    EXPECT_NEAR(f.riser_height_m, 2.9 / 15, 1e-3);
    EXPECT_EQ(f.top_storey - f.bottom_storey, 1);
    ASSERT_GE(f.bottom_storey, 0);
    EXPECT_NEAR(f.rise_m(), o.storey_z_m[static_cast<std::size_t>(f.top_storey)] - o.storey_z_m[static_cast<std::size_t>(f.bottom_storey)], 0.01);
    EXPECT_GT(f.going_m, 0.2);
    EXPECT_GT(f.width_m, 0.8);
  }
}

// The spiral stair ("Wendeltreppe"), an IfcStair body only, in both exports of the house (IFC4:
// closed solids; IFC2X3: a surface model of open shells, faces either way). Hand count: 15 tread
// faces 0.1767 m apart, the last at 2.65 m, 5 cm under the attic's slab top (2.7 m, its storey's
// Elevation); each tread a board 0.06 m thick, a post's top 0.09 m over the last one (not a
// step): 15 risers from the ground floor to the attic. The two files agree on the numbers; the
// IFC2X3 export's treads stand turned about the post (its run line's ends lie 0.3-0.4 m away).
TEST(SharedStairs, FzkHausSpiralStairFromItsBodyInBothSchemas) {
  std::vector<StairFlight> both;
  for (const char* file : {"AC20-FZK-Haus.ifc", "AC11-FZK-Haus-IFC.ifc"}) {
    SCOPED_TRACE(file);
    BIMLOC_REQUIRE_SHARED(path, file);
    const Oracle o = readOracle(path);
    const Building& b = plan(path);
    ASSERT_EQ(b.stairs.size(), o.stairs);
    ASSERT_EQ(b.stairs.size(), 1u);
    const StairFlight& f = b.stairs.front();
    EXPECT_EQ(f.name, "Wendeltreppe");
    EXPECT_EQ(f.source, "body");
    EXPECT_EQ(f.risers, 15);
    EXPECT_NEAR(f.riser_height_m, 2.65 / 15, 1e-3);
    EXPECT_EQ(f.bottom_storey, 0);
    EXPECT_EQ(f.top_storey, 1);
    EXPECT_NEAR(f.rise_m(), o.storey_z_m[1] - o.storey_z_m[0], 0.06);
    both.push_back(f);
  }
  ASSERT_EQ(both.size(), 2u);
  EXPECT_NEAR(both[0].going_m, both[1].going_m, 1e-3);
  EXPECT_NEAR(both[0].width_m, both[1].width_m, 1e-3);
}
