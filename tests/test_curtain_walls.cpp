// Curtain walls as wall landmarks (localizer/src/bim/curtain_walls.cpp): the box of a curtain
// wall's parts, against analytic truth and against the numbers written in SampleHouse4.ifc.
#include "bim/extraction.hpp"
#include "test_support.hpp"

#include <bimloc/bim/ifc_reader.hpp>

#include <gtest/gtest.h>

#include <algorithm>

using namespace bimloc::bim;
using namespace bimloc::bim::detail;

namespace {

// An axis-aligned box [x0, x1] x [y0, y1] x [0, h] as a part of the curtain wall `whole`.
RawProduct part(const char* ifc_class, int whole, double x0, double x1, double y0, double y1, double h) {
  Extrusion ex;
  ex.footprint = {{x0, y0}, {x1, y0}, {x1, y1}, {x0, y1}};
  for (const auto& p : ex.footprint) {
    ex.corners.emplace_back(p.x(), p.y(), 0.0);
    ex.corners.emplace_back(p.x(), p.y(), h);
  }
  ex.z_min = 0.0, ex.z_max = h;
  RawProduct p;
  p.ifc_class = ifc_class;
  p.global_id = std::string(ifc_class) + std::to_string(x0) + "," + std::to_string(y0);
  p.whole_entity_id = whole;
  p.mesh = prismMesh(ex);
  return p;
}

RawProduct curtainWall(int entity_id, const char* global_id) {
  RawProduct cw;  // no body of its own, as Revit writes them
  cw.entity_id = entity_id;
  cw.global_id = global_id;
  cw.ifc_class = "IfcCurtainWall";
  return cw;
}

const Wall* wallWithId(const Storey& storey, const std::string& id) {
  for (const auto& w : storey.walls)
    if (w.id == id) return &w;
  return nullptr;
}

}  // namespace

TEST(CurtainWalls, StraightAssemblyIsOneWallWhoseFacesAreItsOuterSurfaces) {
  RawModel raw;
  raw.elements.push_back(curtainWall(7, "cw"));
  // Three 25 mm glass panels along x in y in [0, 0.025], 30 mm mullions behind them in [-0.03, 0],
  // and an unrelated plate elsewhere (not a part of it).
  for (int i = 0; i < 3; ++i) raw.elements.push_back(part("IfcPlate", 7, 1.5 * i, 1.5 * (i + 1), 0.0, 0.025, 2.7));
  for (int i = 0; i < 4; ++i) raw.elements.push_back(part("IfcMember", 7, 1.5 * i - 0.015, 1.5 * i + 0.015, -0.03, 0.0, 2.7));
  raw.elements.push_back(part("IfcPlate", 0, 10.0, 11.0, 5.0, 5.02, 1.0));
  std::vector<std::string> warnings;
  const auto walls = curtainWallsOf(raw, warnings);
  ASSERT_EQ(walls.size(), 1u);
  EXPECT_TRUE(warnings.empty());
  EXPECT_EQ(walls[0].parts, 7);
  const Wall& w = walls[0].wall;
  EXPECT_EQ(w.id, "cw");
  EXPECT_EQ(w.ifc_type, "IfcCurtainWall");
  EXPECT_NEAR(w.length_m(), 4.5 + 0.03, 1e-5);  // mullion edge to mullion edge
  EXPECT_NEAR(w.thickness_m, 0.055, 1e-5);
  EXPECT_NEAR(w.height_m, 2.7, 1e-5);
  // The box's faces: the glass (y = 0.025, looking +y) and the mullions' back (y = -0.03).
  std::vector<double> ys;
  for (const auto& f : w.faces) ys.push_back(-f.plane.d / f.plane.n.y());
  std::sort(ys.begin(), ys.end());
  EXPECT_NEAR(ys[0], -0.03, 1e-5);
  EXPECT_NEAR(ys[1], 0.025, 1e-5);
  // What a lidar sees: on the glass side the glass; behind, the panels' backs (12.15 m2 at
  // y = 0) between the mullions (0.32 m2 at y = -0.03), 3 cm behind the box's face.
  const auto depth = walls[0].visible_depth_m;
  const bool glass0 = w.faces[0].plane.n.y() > 0;
  EXPECT_NEAR(depth[glass0 ? 0 : 1], 0.0, 1e-5);
  EXPECT_NEAR(depth[glass0 ? 1 : 0], 0.03, 1e-5);
}

TEST(CurtainWalls, FacesLieOnThePanelsWhenDeepMullionsStandInFrontOfThem) {
  // As Jesse.1's curtain walls: 150 mm deep mullions in y in [0, 0.15], 25 mm panels between
  // them set back in y in [0.025, 0.05]. The box's faces are the mullions' fronts; what a
  // lidar sees on either side is the panels: y = 0.05 looking +y (0.10 m behind the front),
  // y = 0.025 looking -y (0.025 m behind the back).
  RawModel raw;
  raw.elements.push_back(curtainWall(7, "deep"));
  for (int i = 0; i < 4; ++i) raw.elements.push_back(part("IfcPlate", 7, 1.5 * i + 0.03, 1.5 * (i + 1) - 0.03, 0.025, 0.05, 3.0));
  for (int i = 0; i < 5; ++i) raw.elements.push_back(part("IfcMember", 7, 1.5 * i - 0.03, 1.5 * i + 0.03, 0.0, 0.15, 3.0));
  std::vector<std::string> warnings;
  auto walls = curtainWallsOf(raw, warnings);
  ASSERT_EQ(walls.size(), 1u);
  Wall w = walls[0].wall;
  EXPECT_NEAR(w.thickness_m, 0.15, 1e-5);
  moveFacesToVisibleSurfaces(w, walls[0].visible_depth_m);
  for (const auto& f : w.faces) {
    const double y = -f.plane.d / f.plane.n.y();
    EXPECT_NEAR(y, f.plane.n.y() > 0 ? 0.05 : 0.025, 1e-5);
    EXPECT_NEAR(f.start.y(), y, 1e-5);  // the face's corners moved with its plane
    EXPECT_NEAR(f.end.y(), y, 1e-5);
  }
  EXPECT_NEAR(w.thickness_m, 0.15, 1e-5);  // the box (what rooms are linked to) is kept
  EXPECT_NEAR(w.start.y(), walls[0].wall.start.y(), 1e-12);
}

TEST(CurtainWalls, BentAssemblyIsNoWallAndIsNamedInTheWarnings) {
  RawModel raw;
  raw.elements.push_back(curtainWall(7, "corner"));
  raw.elements.push_back(part("IfcPlate", 7, 0.0, 4.0, 0.0, 0.025, 2.7));    // along x
  raw.elements.push_back(part("IfcPlate", 7, 3.975, 4.0, 0.0, 4.0, 2.7));    // turning along y
  std::vector<std::string> warnings;
  EXPECT_TRUE(curtainWallsOf(raw, warnings).empty());
  ASSERT_EQ(warnings.size(), 1u);
  EXPECT_NE(warnings[0].find("corner"), std::string::npos) << warnings[0];
  EXPECT_NE(warnings[0].find("no single plane"), std::string::npos) << warnings[0];
}

TEST(CurtainWalls, CurtainWallWithoutAnyGeometryIsNamedInTheWarnings) {
  RawModel raw;
  raw.elements.push_back(curtainWall(7, "empty"));
  std::vector<std::string> warnings;
  EXPECT_TRUE(curtainWallsOf(raw, warnings).empty());
  ASSERT_EQ(warnings.size(), 1u);
  EXPECT_NE(warnings[0].find("empty"), std::string::npos) << warnings[0];
}

TEST(CurtainWalls, RoomEdgeInsideTheWallBodyIsBoundedByTheFaceLookingIn) {
  // A wall along x, faces at y = 0 (looking -y, its back) and y = 0.065 (looking +y); a room
  // north of it drawn to the wall's centre line, and one drawn 5 cm behind its back.
  Wall w;
  w.thickness_m = 0.065;
  w.faces[1].plane.n = Eigen::Vector3d(0, 1, 0), w.faces[1].plane.d = -0.065;
  w.faces[1].start = Eigen::Vector3d(0, 0.065, 0), w.faces[1].end = Eigen::Vector3d(5, 0.065, 0);
  w.faces[0].plane.n = Eigen::Vector3d(0, -1, 0), w.faces[0].plane.d = 0.0;
  w.faces[0].start = Eigen::Vector3d(5, 0, 0), w.faces[0].end = Eigen::Vector3d(0, 0, 0);
  const ExtractOptions options;  // 5 cm, 5 degrees, 0.2 m overlap
  // A counter-clockwise room's south edge runs +x, its inside to the left (+y).
  EXPECT_TRUE(edgeInWallBody(w, 1, {-1, 0.0325}, {6, 0.0325}, options));   // centre line
  EXPECT_TRUE(edgeInWallBody(w, 1, {0, 0.0}, {5, 0.0}, options));          // the back
  EXPECT_TRUE(edgeInWallBody(w, 1, {0, 0.065}, {5, 0.065}, options));      // the face itself
  EXPECT_FALSE(edgeInWallBody(w, 1, {0, -0.1}, {5, -0.1}, options));       // 10 cm behind the back
  EXPECT_FALSE(edgeInWallBody(w, 1, {0, 0.2}, {5, 0.2}, options));         // in the room, off the face
  EXPECT_FALSE(edgeInWallBody(w, 0, {0, 0.0325}, {5, 0.0325}, options));   // the back does not look in
  EXPECT_FALSE(edgeInWallBody(w, 1, {5.1, 0.0325}, {8, 0.0325}, options)); // beside the wall
}

// SampleHouse4.ifc's two curtain walls (Revit 2015): glazed IfcPlate panels and 30 mm IfcMember
// mullions, aggregated by IfcCurtainWall entities that have no body of their own. The numbers
// below are the file's (millimetres): the west wall's panel #2470 is placed at
// x = -7710.34849347184 and extruded 25 mm towards the room, its panels run from
// y = -1246.4176 to 4408.5822 (walls #1752/#2327 meet it there); the south wall's panel #3858
// is placed at y = -1221.91766651718, 25 mm deep, and its three panels of 1633.333 mm run from
// x = -7734.84849347185.
TEST(CurtainWalls, SampleHouse4GetsItsTwoCurtainWallsWhereTheFilePutsThem) {
  BIMLOC_REQUIRE_SHARED(path, "SampleHouse4.ifc");
  const Building b = readIfc(path);
  const Storey& ground = b.storeys.at(0);
  const Wall* west = wallWithId(ground, "3cUkl32yn9qRSPvBJVyW_P");
  const Wall* south = wallWithId(ground, "3cUkl32yn9qRSPvBJVyW$Z");
  ASSERT_TRUE(west && south);
  EXPECT_EQ(west->ifc_type, "IfcCurtainWall");
  EXPECT_EQ(south->ifc_type, "IfcCurtainWall");
  constexpr double kMm = 1e-3;
  // The face that looks into the house (+x for the west wall, +y for the south one) is the glass.
  const auto inner = [](const Wall& w, const Eigen::Vector3d& n) -> const WallFace& {
    return w.faces[0].plane.n.dot(n) > 0.99 ? w.faces[0] : w.faces[1];
  };
  const WallFace& w_in = inner(*west, Eigen::Vector3d::UnitX());
  ASSERT_GT(w_in.plane.n.x(), 0.99);
  EXPECT_NEAR(-w_in.plane.d, (-7710.34849347184 + 25.0) * kMm, 1 * kMm);
  EXPECT_NEAR(west->length_m(), (4408.5822 + 1246.4176) * kMm, 1 * kMm);
  const WallFace& s_in = inner(*south, Eigen::Vector3d::UnitY());
  ASSERT_GT(s_in.plane.n.y(), 0.99);
  EXPECT_NEAR(-s_in.plane.d, (-1221.91766651718 + 25.0) * kMm, 1 * kMm);
  EXPECT_NEAR(south->length_m(), 3 * 1633.33333333333 * kMm, 1 * kMm);
  EXPECT_NEAR(std::min(south->start.x(), south->end.x()), -7734.84849347185 * kMm, 1 * kMm);
  // The living room (drawn to the assembly's outer line) is bounded by both, by the glass face.
  const Room* living = ground.findRoom("1 - Living room");
  ASSERT_TRUE(living);
  int linked = 0;
  for (const auto& link : living->walls) {
    if (link.wall_id != west->id && link.wall_id != south->id) continue;
    ++linked;
    const Wall& w = link.wall_id == west->id ? *west : *south;
    ASSERT_GE(link.face, 0);
    EXPECT_EQ(&w.faces[static_cast<std::size_t>(link.face)], link.wall_id == west->id ? &w_in : &s_in);
  }
  EXPECT_EQ(linked, 2);
}
