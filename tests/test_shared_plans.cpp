// The nine real plans of ../shared/ifc, against the entity counts of SOURCES.md and against
// each other (the same house exported to IFC2X3 and IFC4). Skips when the folder is absent.
#include "test_support.hpp"

#include <bimloc/bim/geometry2d.hpp>
#include <bimloc/bim/ifc_reader.hpp>

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <map>

using namespace bimloc::bim;

namespace {

struct Expected {
  const char* file;
  const char* schema;
  std::size_t storeys, spaces, walls;
};

// SOURCES.md: storeys, IfcSpace, walls (IfcWall + IfcWallStandardCase, and the straight
// curtain walls: SampleHouse4 2, Jesse.1 10).
const Expected kPlans[] = {
    {"AC20-FZK-Haus.ifc", "IFC4", 2, 7, 13},     {"AC11-FZK-Haus-IFC.ifc", "IFC2X3", 2, 7, 13},
    {"Duplex_A_20110907.ifc", "IFC2X3", 4, 21, 57}, {"SampleHouse4.ifc", "IFC4", 2, 4, 5 + 2},
    {"revit_quantities.ifc", "IFC2X3", 1, 7, 10},  {"ExampleHOM.ifc", "IFC4", 3, 11, 20},
    {"AC90R1-Jasmin-Sun-105-2x3.ifc", "IFC2X3", 3, 10, 19}, {"example.ifc", "IFC2X3", 1, 4, 18},
    {"Jesse.1.ifc", "IFC2X3", 8, 0, 160 + 10},
};

// Printed in test names and failures as the file name, not as bytes.
void PrintTo(const Expected& e, std::ostream* os) { *os << e.file; }

// Plans are read once per test binary: the suite reads each several times otherwise.
const Building& plan(const std::string& path) {
  static std::map<std::string, Building> cache;
  auto it = cache.find(path);
  if (it == cache.end()) it = cache.emplace(path, readIfc(path)).first;
  return it->second;
}

class SharedPlan : public ::testing::TestWithParam<Expected> {};

std::size_t total(const Building& b, std::size_t (*count)(const Storey&)) {
  std::size_t n = 0;
  for (const auto& s : b.storeys) n += count(s);
  return n;
}

}  // namespace

TEST_P(SharedPlan, CountsMatchSources) {
  BIMLOC_REQUIRE_SHARED(path, GetParam().file);
  const Building& b = plan(path);
  EXPECT_EQ(b.schema, GetParam().schema);
  EXPECT_EQ(b.storeys.size(), GetParam().storeys);
  // Rooms from IfcSpace; a storey with walls and no IfcSpace has inferred rooms besides.
  EXPECT_EQ(total(b,
                  [](const Storey& s) {
                    return static_cast<std::size_t>(std::count_if(s.rooms.begin(), s.rooms.end(), [](const Room& r) {
                      return r.source == "IfcSpace";
                    }));
                  }),
            GetParam().spaces);
  EXPECT_EQ(total(b, [](const Storey& s) { return s.walls.size(); }), GetParam().walls);
  for (std::size_t i = 1; i < b.storeys.size(); ++i) EXPECT_LE(b.storeys[i - 1].elevation_m, b.storeys[i].elevation_m);
}

TEST_P(SharedPlan, EveryWallYieldsTwoOutwardUnitFaces) {
  BIMLOC_REQUIRE_SHARED(path, GetParam().file);
  for (const auto& s : plan(path).storeys)
    for (const auto& w : s.walls) {
      EXPECT_GT(w.thickness_m, 0.0) << w.id;
      EXPECT_GT(w.height_m, 0.0) << w.id;
      const Eigen::Vector3d axis_mid = 0.5 * (w.start + w.end);
      // A face is the box's side; a curtain wall's may lie further in, on its panels
      // (curtain_walls.cpp), but inside the box and not past the other face.
      double depths = 0.0;
      for (const auto& f : w.faces) {
        EXPECT_NEAR(f.plane.n.norm(), 1.0, 1e-9) << w.id;
        const double depth = f.plane.signedDistance(axis_mid) + 0.5 * w.thickness_m;
        if (w.ifc_type == "IfcCurtainWall") EXPECT_GE(depth, -1e-6) << w.id;
        else EXPECT_NEAR(depth, 0.0, 1e-6) << w.id;
        depths += depth;
      }
      EXPECT_LE(depths, w.thickness_m + 1e-6) << w.id;
    }
}

TEST_P(SharedPlan, RoomsHaveAreaAndEveryRoomWithWallsLinksFacesLookingIn) {
  BIMLOC_REQUIRE_SHARED(path, GetParam().file);
  for (const auto& s : plan(path).storeys)
    for (const auto& r : s.rooms) {
      EXPECT_GT(r.area_m2, 0.5) << r.name;
      EXPECT_GE(r.footprint.size(), 3u) << r.name;
      for (const auto& rw : r.walls) EXPECT_NE(s.findWall(rw.wall_id), nullptr) << r.name;
    }
}

INSTANTIATE_TEST_SUITE_P(Plans, SharedPlan, ::testing::ValuesIn(kPlans),
                         [](const ::testing::TestParamInfo<Expected>& p) {
                           std::string n = p.param.file;
                           for (char& c : n) if (!std::isalnum(static_cast<unsigned char>(c))) c = '_';
                           return n;
                         });

TEST(SharedPlans, FzkHausIfc2x3AndIfc4GiveTheSameRoomsAndWallPlanes) {
  BIMLOC_REQUIRE_SHARED(ifc4, "AC20-FZK-Haus.ifc");
  BIMLOC_REQUIRE_SHARED(ifc2x3, "AC11-FZK-Haus-IFC.ifc");
  const Building& a = plan(ifc4);
  const Building& b = plan(ifc2x3);
  ASSERT_EQ(a.storeys.size(), b.storeys.size());
  for (std::size_t s = 0; s < a.storeys.size(); ++s) {
    const auto& sa = a.storeys[s];
    const auto& sb = b.storeys[s];
    EXPECT_NEAR(sa.elevation_m, sb.elevation_m, 1e-6);
    ASSERT_EQ(sa.rooms.size(), sb.rooms.size());
    for (const auto& ra : sa.rooms) {
      // Same room: same Name (GlobalIds differ between the two exports).
      const Room* rb = sb.findRoom(ra.name);
      ASSERT_NE(rb, nullptr) << ra.name;
      EXPECT_EQ(rb->long_name, ra.long_name);  // UTF-8 from \X2\ escapes: "Küche"
      // The same wall faces bound it, to 1 cm.
      ASSERT_EQ(rb->walls.size(), ra.walls.size()) << ra.name;
      for (const auto& wa : ra.walls) {
        const Plane& pa = sa.findWall(wa.wall_id)->faces[static_cast<std::size_t>(wa.face)].plane;
        bool found = false;
        for (const auto& wb : rb->walls) {
          const Plane& pb = sb.findWall(wb.wall_id)->faces[static_cast<std::size_t>(wb.face)].plane;
          found |= pa.n.dot(pb.n) > std::cos(0.5 * M_PI / 180) && std::abs(pa.d - pb.d) < 0.01;
        }
        EXPECT_TRUE(found) << ra.name << ": wall " << wa.wall_id;
      }
      // The footprints agree wherever walls bound them. The open-plan kitchen / living room
      // pair (Names 5 and 6) is split by an IfcVirtualElement that the two exports put at
      // x = 4.70 and 4.99 m: the files differ there, so that pair is compared as a whole.
      const bool open_plan = ra.name == "5" || ra.name == "6";
      if (!open_plan) {
        EXPECT_NEAR((rb->centre - ra.centre).norm(), 0.0, 0.01) << ra.name;
        EXPECT_NEAR(rb->area_m2, ra.area_m2, 0.01 * ra.area_m2) << ra.name;
      } else {
        EXPECT_NEAR(rb->area_m2 + (ra.name == "5" ? sb.findRoom("6") : sb.findRoom("5"))->area_m2,
                    ra.area_m2 + (ra.name == "5" ? sa.findRoom("6") : sa.findRoom("5"))->area_m2, 0.01)
            << "kitchen + living room together";
      }
    }
    ASSERT_EQ(sa.walls.size(), sb.walls.size());
    for (const auto& wa : sa.walls)
      for (const auto& fa : wa.faces) {
        double best = 1e9;
        for (const auto& wb : sb.walls)
          for (const auto& fb : wb.faces)
            if (fa.plane.n.dot(fb.plane.n) > std::cos(0.5 * M_PI / 180))
              best = std::min(best, std::abs(fa.plane.d - fb.plane.d));
        EXPECT_LT(best, 0.01) << wa.name;
      }
  }
}

TEST(SharedPlans, SampleHouse4ComesOutInMetres) {
  BIMLOC_REQUIRE_SHARED(path, "SampleHouse4.ifc");
  const Building& b = plan(path);
  ASSERT_EQ(b.storeys.size(), 2u);
  EXPECT_NEAR(b.storeys[1].elevation_m, 2.5, 1e-6);  // 2500 mm in the file
  for (const auto& w : b.storeys[0].walls) {
    EXPECT_GT(w.thickness_m, 0.05);
    EXPECT_LT(w.thickness_m, 1.0);
    EXPECT_GT(w.height_m, 1.0);
    EXPECT_LT(w.height_m, 10.0);
  }
  for (const auto& r : b.storeys[0].rooms) EXPECT_LT(r.area_m2, 200.0) << r.name;
}

TEST(SharedPlans, ExampleHomStoreysTakeTheirElevationFromPlacements) {
  BIMLOC_REQUIRE_SHARED(path, "ExampleHOM.ifc");
  const Building& b = plan(path);
  ASSERT_EQ(b.storeys.size(), 3u);
  for (const auto& s : b.storeys) EXPECT_EQ(s.elevation_source, "placement") << s.name;
  EXPECT_NEAR(b.storeys[0].elevation_m, 0.0, 1e-6);
  EXPECT_GT(b.storeys[1].elevation_m, 2.0);
  EXPECT_GT(b.storeys[2].elevation_m, b.storeys[1].elevation_m + 2.0);
  // Most walls have no mesh from IFC++: they must come from their profiles.
  std::size_t from_profile = 0;
  for (const auto& s : b.storeys)
    for (const auto& w : s.walls) from_profile += w.source == "profile";
  EXPECT_GE(from_profile, 10u);
}

TEST(SharedPlans, DuplexElevationsMatchSources) {
  BIMLOC_REQUIRE_SHARED(path, "Duplex_A_20110907.ifc");
  const Building& b = plan(path);
  const double expected[] = {-1.25, 0.0, 3.1, 6.0};
  ASSERT_EQ(b.storeys.size(), 4u);
  for (std::size_t i = 0; i < 4; ++i) EXPECT_NEAR(b.storeys[i].elevation_m, expected[i], 1e-6);
}

TEST(SharedPlans, JasminSunHasACellarAndAnAtticStorey) {
  BIMLOC_REQUIRE_SHARED(path, "AC90R1-Jasmin-Sun-105-2x3.ifc");
  const Building& b = plan(path);
  const double expected[] = {-2.9, 0.0, 2.9};  // SOURCES.md
  const std::size_t rooms[] = {3, 4, 3};
  ASSERT_EQ(b.storeys.size(), 3u);
  for (std::size_t i = 0; i < 3; ++i) {
    EXPECT_NEAR(b.storeys[i].elevation_m, expected[i], 1e-6);
    EXPECT_EQ(b.storeys[i].rooms.size(), rooms[i]) << b.storeys[i].name;
    for (const auto& r : b.storeys[i].rooms) EXPECT_FALSE(r.walls.empty()) << r.name;
  }
}

TEST(SharedPlans, ExampleIfcNamesItsTwoApproximatedOuterWalls) {
  BIMLOC_REQUIRE_SHARED(path, "example.ifc");
  const Building& b = plan(path);
  std::vector<std::string> approximated;
  for (const auto& w : b.storeys[0].walls)
    if (w.approximated) approximated.push_back(w.name);
  std::sort(approximated.begin(), approximated.end());
  ASSERT_EQ(approximated, (std::vector<std::string>{"Outer Wall IV", "Outer Wall XII"}));
  for (const auto& name : approximated) {
    bool warned = false;
    for (const auto& w : b.warnings) warned |= w.find(name) != std::string::npos && w.find("approximated") != std::string::npos;
    EXPECT_TRUE(warned) << name;
  }
  // Its one storey holds two levels (walls at z = 0 and 3.1 m), and rooms on both.
  std::size_t upper = 0;
  for (const auto& r : b.storeys[0].rooms) upper += r.floor_z > 3.0;
  EXPECT_EQ(upper, 2u);
}

TEST(SharedPlans, JesseHasNoIfcSpaceSoRoomsAreInferredOnTheStoreysWithWalls) {
  BIMLOC_REQUIRE_SHARED(path, "Jesse.1.ifc");
  const Building& b = plan(path);
  ASSERT_EQ(b.storeys.size(), 8u);
  EXPECT_NEAR(b.storeys.front().elevation_m, -1.26, 1e-6);  // millimetres in the file
  EXPECT_NEAR(b.storeys.back().elevation_m, 8.74, 1e-6);
  std::printf("Jesse.1.ifc: storey, walls, inferred rooms (parse %.2f s, geometry %.2f s, model with inference %.2f s)\n",
              b.times.parse_s, b.times.geometry_s, b.times.model_s);
  std::size_t with_rooms = 0;
  for (const auto& s : b.storeys) {
    std::printf("  %-20s z %6.2f  walls %3zu  rooms %3zu\n", s.name.c_str(), s.elevation_m, s.walls.size(), s.rooms.size());
    const std::string announced = "storey '" + s.name + "': no IfcSpace, " + std::to_string(s.rooms.size()) + " rooms inferred";
    bool warned = false;
    for (const auto& w : b.warnings) warned |= w.rfind(announced, 0) == 0;
    EXPECT_EQ(warned, !s.walls.empty()) << s.name;  // storeys without walls: no rooms, no word
    if (s.walls.empty()) {
      EXPECT_TRUE(s.rooms.empty()) << s.name;
    }
    with_rooms += !s.rooms.empty();
    for (std::size_t i = 0; i < s.rooms.size(); ++i) {
      const Room& r = s.rooms[i];
      EXPECT_EQ(r.source, "inferred");
      EXPECT_GE(r.area_m2, 1.0) << s.name << " " << r.name;
      EXPECT_GT(signedArea(r.footprint), 0.0) << s.name << " " << r.name;
      EXPECT_NEAR(r.area_m2, signedArea(r.footprint), 1e-9);
      for (std::size_t j = i + 1; j < s.rooms.size(); ++j)  // rooms of one level never overlap
        if (std::abs(s.rooms[j].floor_z - r.floor_z) < 0.3) {
          EXPECT_LT(polygonIoU(r.footprint, s.rooms[j].footprint), 0.01) << r.name << " / " << s.rooms[j].name;
        }
    }
  }
  // The basement, and the main floors: the building's rooms are there.
  EXPECT_GE(b.findStorey("Level -1")->rooms.size(), 20u);
  EXPECT_GE(b.findStorey("Level 1")->rooms.size(), 10u);
  EXPECT_GE(with_rooms, 4u);
  // "T.O. level 1 floor" has only 0.36 m high walls (curbs): no rooms, and the walls are named.
  EXPECT_TRUE(b.findStorey("T.O. level 1 floor")->rooms.empty());
  // Same file, same rooms.
  const Building again = readIfc(path);
  for (std::size_t s = 0; s < b.storeys.size(); ++s) {
    ASSERT_EQ(again.storeys[s].rooms.size(), b.storeys[s].rooms.size());
    for (std::size_t i = 0; i < b.storeys[s].rooms.size(); ++i)
      EXPECT_EQ(again.storeys[s].rooms[i].footprint, b.storeys[s].rooms[i].footprint);
  }
}
