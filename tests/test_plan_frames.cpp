// Where a plan puts its building: a site above sea level, a site at surveyed (georeferenced)
// coordinates, a storey height that is no floor's. The oracle is the same plan placed at the
// origin: what is read must be the same building (bim/storey_levels.cpp, bim/map_origin.hpp).
#include "plan_mutation.hpp"
#include "test_support.hpp"

#include <bimloc/bim/building_json.hpp>
#include <bimloc/bim/ifc_reader.hpp>

#include "bim/extraction.hpp"
#include "bim/raw_model.hpp"

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <cstdio>
#include <optional>
#include <vector>
#include <string>

using bimloc::test::anyWarningHas;
using bimloc::test::mutated;
using bimloc::test::runBimloc;
using bimloc::test::slurp;
using bimloc::test::tempDir;
using bimloc::test::writeFile;
namespace bim = bimloc::bim;

namespace {

std::string plainPlan() { return slurp(std::string(BIMLOC_WORLDS_DIR) + "/site_office.ifc"); }

// site_office with its site's root placement (#15, which shares #4 with every wall) at (x, y, z).
std::string siteAt(double x, double y, double z) {
  char point[160];
  std::snprintf(point, sizeof point, "#9003=IFCCARTESIANPOINT((%.17g,%.17g,%.17g));\n#9004=IFCAXIS2PLACEMENT3D(#9003,#1,#2);\n", x, y, z);
  return mutated(plainPlan(), "#15=IFCLOCALPLACEMENT($,#4);", std::string(point) + "#15=IFCLOCALPLACEMENT($,#9004);");
}

// Whether one warning of the extraction holds both strings (anyWarningHas, for a Building).
bool warned(const bim::Building& b, const std::string& a, const std::string& c = "") {
  for (const auto& w : b.warnings)
    if (w.find(a) != std::string::npos && w.find(c) != std::string::npos) return true;
  return false;
}

// A 2 s run of R101 on the plan: what a damaged plan must get through without a crash.
bimloc::test::CommandResult runBriefly(const std::string& plan) {
  return runBimloc("run --plan '" + plan + "' --all-rooms --rooms R101 --duration 2 --jobs 1");
}

bool converges(const std::string& plan, const std::string& room) {
  const auto r = runBimloc("run --plan '" + plan + "' --all-rooms --rooms " + room + " --duration 25 --jobs 1 --json");
  const auto doc = nlohmann::json::parse(r.out, nullptr, false);
  if (doc.is_discarded() || !doc.contains("scenarios") || doc["scenarios"].empty()) return false;
  return doc["scenarios"][0].value("converged", false) && !doc["scenarios"][0].value("false_convergence", true);
}

}  // namespace

// A site 400 m above sea level whose storey's Elevation says 0 (relative to the building, as
// the schema has it): the floor is where the walls stand, and the robot localizes as on the
// plan at sea level. Before, the floor was 400 m below the walls and the robot fell.
TEST(PlanFrames, ASiteAboveSeaLevelPutsTheFloorUnderItsWalls) {
  const auto dir = tempDir("plan-frames-height");
  const std::string high = writeFile(dir, "high.ifc", siteAt(0, 0, 400));
  const bim::Building plain = bim::readIfc(writeFile(dir, "plain.ifc", plainPlan())), b = bim::readIfc(high);
  ASSERT_EQ(b.storeys.size(), 1u);
  EXPECT_NEAR(b.storeys[0].elevation_m, 400.0, 1e-9);
  EXPECT_EQ(b.storeys[0].elevation_source, "placement");
  EXPECT_TRUE(warned(b, "Elevation 0.000 m, placed at 400.000 m"));
  ASSERT_EQ(b.storeys[0].walls.size(), plain.storeys[0].walls.size());
  for (std::size_t k = 0; k < b.storeys[0].walls.size(); ++k)
    EXPECT_NEAR(b.storeys[0].walls[k].start.z() - plain.storeys[0].walls[k].start.z(), 400.0, 1e-6);
  EXPECT_EQ(plain.storeys[0].elevation_source, "Elevation");  // Elevation and placement agree: no warning
  EXPECT_TRUE(plain.warnings.empty());
  EXPECT_TRUE(converges(high, "R101"));
}

// At UTM coordinates (northing 5 500 000 m) a float holds half a metre: IFC++'s cuts lost three
// walls and the runs' ATE was 0.115 m. The site is moved near the origin by whole metres, and
// the plan reads as the same plan at the origin, bit for bit, with the offset named.
TEST(PlanFrames, AGeoreferencedSiteReadsAsThePlanAtTheOriginAndNamesTheOffset) {
  const auto dir = tempDir("plan-frames-geo");
  const bim::Building plain = bim::readIfc(writeFile(dir, "plain.ifc", plainPlan()));
  const std::string utm = writeFile(dir, "utm.ifc", siteAt(500000, 5500000, 0));
  const bim::Building b = bim::readIfc(utm);
  EXPECT_EQ(b.map_origin_in_plan_m.x(), 500000.0);
  EXPECT_EQ(b.map_origin_in_plan_m.y(), 5500000.0);
  EXPECT_TRUE(warned(b, "moved by (-500000, -5500000) m"));
  nlohmann::json a = bim::toJson(b), p = bim::toJson(plain);
  EXPECT_EQ(a["map_origin_in_plan_m"], nlohmann::json::array({500000.0, 5500000.0}));
  EXPECT_EQ(a["storeys"], p["storeys"]);
  // The offset survives building.json, and a damaged one is refused.
  EXPECT_EQ(bim::buildingFromJson(a).map_origin_in_plan_m, b.map_origin_in_plan_m);
  a["map_origin_in_plan_m"] = nlohmann::json::array({1.0});
  EXPECT_THROW(bim::buildingFromJson(a), std::runtime_error);
  EXPECT_FALSE(p.contains("map_origin_in_plan_m"));  // a plan at its origin: the document as before
  // Off by a fraction of a metre: the fraction stays in the map frame.
  const bim::Building f = bim::readIfc(writeFile(dir, "frac.ifc", siteAt(2600000.25, 1200000.375, 0)));
  EXPECT_EQ(f.map_origin_in_plan_m, Eigen::Vector2d(2600000.0, 1200000.0));
  ASSERT_EQ(f.storeys[0].walls.size(), plain.storeys[0].walls.size());
  for (std::size_t k = 0; k < f.storeys[0].walls.size(); ++k)
    for (std::size_t s = 0; s < 2; ++s)
      EXPECT_LT((f.storeys[0].walls[k].faces[s].start - plain.storeys[0].walls[k].faces[s].start - Eigen::Vector3d(0.25, 0.375, 0)).norm(), 1e-6);
  EXPECT_TRUE(converges(utm, "R101"));
  // The walls hung from a far placement under a storey at the origin (29 placements moved to
  // #9021): moved by their middle, whole metres; the walls are the plain plan's less the
  // offset's part beyond the far placement, none lost (IFC++'s cuts lost 3 at UTM before).
  std::string text = plainPlan();
  for (std::size_t at = text.find("IFCLOCALPLACEMENT(#21,"); at != std::string::npos; at = text.find("IFCLOCALPLACEMENT(#21,", at))
    text.replace(at, 22, "IFCLOCALPLACEMENT(#9021,");
  text = mutated(text, "#22=IFCBUILDINGSTOREY(",
                 "#9003=IFCCARTESIANPOINT((500000.,5500000.,0.));\n#9004=IFCAXIS2PLACEMENT3D(#9003,#1,#2);\n"
                 "#9021=IFCLOCALPLACEMENT(#21,#9004);\n#22=IFCBUILDINGSTOREY(");
  const bim::Building e = bim::readIfc(writeFile(dir, "walls_far.ifc", text));
  const Eigen::Vector2d beyond = e.map_origin_in_plan_m - Eigen::Vector2d(500000, 5500000);
  EXPECT_LT(beyond.norm(), 50.0) << e.map_origin_in_plan_m.transpose();
  EXPECT_EQ(beyond, beyond.array().round().matrix());
  ASSERT_EQ(e.storeys[0].walls.size(), plain.storeys[0].walls.size());
  for (std::size_t k = 0; k < e.storeys[0].walls.size(); ++k)
    EXPECT_LT((e.storeys[0].walls[k].faces[0].start.head<2>() + beyond - plain.storeys[0].walls[k].faces[0].start.head<2>()).norm(), 1e-6);
}

// A storey written at -1e300 m (one damaged number) aborted the ray caster (an assertion in
// Embree): the height is named and ignored, the placement's taken.
TEST(PlanFrames, AStoreyHeightThatIsNoFloorsIsNamedAndIgnored) {
  const auto dir = tempDir("plan-frames-damaged");
  const std::string text = plainPlan();
  const std::string from = "'Ground floor',$,$,#21,$,$,.ELEMENT.,0.);";
  ASSERT_NE(text.find(from), std::string::npos);
  const std::string path = writeFile(dir, "deep.ifc", mutated(text, from, "'Ground floor',$,$,#21,$,$,.ELEMENT.,-1.E300);"));
  const bim::Building b = bim::readIfc(path);
  EXPECT_EQ(b.storeys[0].elevation_m, 0.0);
  EXPECT_TRUE(warned(b, "'Ground floor': Elevation", "is no floor's height"));
  const auto r = runBriefly(path);
  EXPECT_EQ(r.signal, 0) << r.err;
  EXPECT_TRUE(r.exit_code == 0 || r.exit_code == 1) << r.err;
}

// A wall 5 km long (one damaged profile length): the storey is 5 km long. The simulator's path
// grid (0.05 m cells, stored where its searches go) holds it, and the run runs. A wall 5 km
// long and 5 km thick makes the storey too large for it (1e10 cells): the run names the plan,
// the storey and its size. (The count was once an int cast from a double: 1e9 m read
// 18446743431611941163 cells.)
TEST(PlanFrames, AStoreyTooLargeForThePathGridIsNamedWithItsSize) {
  const auto dir = tempDir("plan-frames-huge");
  const std::string text = plainPlan();
  const std::string from = "#32=IFCRECTANGLEPROFILEDEF(.AREA.,$,#31,22.2,0.3);";
  ASSERT_NE(text.find(from), std::string::npos);
  const std::string path = writeFile(dir, "long.ifc", mutated(text, from, "#32=IFCRECTANGLEPROFILEDEF(.AREA.,$,#31,5000.,0.3);"));
  auto r = runBriefly(path);
  EXPECT_EQ(r.signal, 0) << r.err;
  EXPECT_TRUE(r.exit_code == 0 || r.exit_code == 1) << r.err;
  EXPECT_EQ(r.err.find("too large for the path grid"), std::string::npos) << r.err;
  const std::string huge = writeFile(dir, "huge.ifc", mutated(text, from, "#32=IFCRECTANGLEPROFILEDEF(.AREA.,$,#31,5000.,5000.);"));
  r = runBriefly(huge);
  EXPECT_EQ(r.exit_code, 1) << r.err;
  EXPECT_NE(r.err.find("huge.ifc: storey 'Ground floor' spans 50"), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("too large for the path grid"), std::string::npos) << r.err;
}

// One room vertex written 1e30 m out overflowed the simulator's room lookup and segfaulted the
// filter's room index. From the IFC the room is skipped and named; from building.json the
// document is refused, naming the place. A plan whose vertices all carry surveyed coordinates
// (no placement moves them) is still read: "far" is from the middle of its walls.
TEST(PlanFrames, AnElementFarBeyondAnyPlanIsSkippedOrRefusedByName) {
  const auto dir = tempDir("plan-frames-far");
  const std::string text = plainPlan();
  const std::string from = "#692=IFCCARTESIANPOINT((4.12,7.24));";  // a corner of R106's footprint
  ASSERT_NE(text.find(from), std::string::npos);
  const std::string path = writeFile(dir, "far.ifc", mutated(text, from, "#692=IFCCARTESIANPOINT((1.E30,7.24));"));
  const bim::Building plain = bim::readIfc(writeFile(dir, "plain.ifc", text)), b = bim::readIfc(path);
  EXPECT_EQ(b.storeys[0].rooms.size() + 1, plain.storeys[0].rooms.size());
  EXPECT_TRUE(warned(b, "'R106': room skipped: a coordinate 1e+30 m from the middle of the plan's walls"));
  const auto r = runBriefly(path);
  EXPECT_EQ(r.signal, 0) << r.err;
  EXPECT_TRUE(r.exit_code == 0 || r.exit_code == 1) << r.err;
  nlohmann::json doc = bim::toJson(plain);
  doc["storeys"][0]["rooms"][3]["footprint"][1] = nlohmann::json::array({1e30, 7.0});
  try {
    bim::buildingFromJson(doc);
    ADD_FAILURE() << "a room 1e30 m long was read";
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find("storeys[0].rooms[3]: a coordinate 1e+30 m from the middle"), std::string::npos) << e.what();
  }
}

// The rule of each storey's level, case by case, on raw storeys (storey_levels.cpp).
TEST(PlanFrames, EachStoreyLevelComesFromWhereTheGeometryIs) {
  namespace d = bimloc::bim::detail;
  const auto storey = [](int id, std::optional<double> elevation, double placed) {
    d::RawStorey s;
    s.entity_id = id, s.global_id = "g" + std::to_string(id), s.name = "S" + std::to_string(id);
    s.elevation_m = elevation, s.placement_z_m = placed;
    return s;
  };
  const auto levels = [](std::vector<d::RawStorey> storeys, std::vector<std::string>& warnings) {
    d::RawModel raw;
    raw.storeys = std::move(storeys);
    return d::storeyLevels(raw, warnings);
  };
  std::vector<std::string> w;
  // Both agree (within a millimetre): Elevation as written, no warning.
  auto l = levels({storey(1, 3.1000000000004, 3.1), storey(2, 0.0, 0.0)}, w);
  EXPECT_EQ(l[0].elevation_m, 3.1000000000004);
  EXPECT_EQ(l[0].source, "Elevation");
  EXPECT_TRUE(w.empty());
  // A site 400 m up: the placements, each named.
  l = levels({storey(1, 0.0, 400.0), storey(2, 3.0, 403.0)}, w);
  EXPECT_EQ(l[0].elevation_m, 400.0);
  EXPECT_EQ(l[1].elevation_m, 403.0);
  EXPECT_EQ(l[1].source, "placement");
  EXPECT_EQ(w.size(), 2u);
  // Placements that do not tell the storeys apart: Elevation.
  w.clear();
  l = levels({storey(1, 0.0, 0.0), storey(2, 3.0, 0.0)}, w);
  EXPECT_EQ(l[1].elevation_m, 3.0);
  EXPECT_EQ(l[1].source, "Elevation");
  // No Elevation: the placement (ExampleHOM).
  l = levels({storey(1, std::nullopt, 2.875)}, w);
  EXPECT_EQ(l[0].elevation_m, 2.875);
  EXPECT_EQ(l[0].source, "placement");
  // An Elevation no floor has: named and ignored; neither usable: 0 m, named.
  w.clear();
  l = levels({storey(1, -1e300, 0.0), storey(2, std::nullopt, 1e30)}, w);
  EXPECT_EQ(l[0].elevation_m, 0.0);
  EXPECT_EQ(l[0].source, "placement");
  EXPECT_EQ(l[1].source, "none");
  EXPECT_EQ(l[1].elevation_m, 0.0);
  ASSERT_EQ(w.size(), 2u);
  EXPECT_NE(w[0].find("'S1': Elevation -1e+300"), std::string::npos) << w[0];
  EXPECT_NE(w[1].find("'S2': neither its Elevation nor its placement"), std::string::npos) << w[1];
}
