// Rooms inferred from walls, against analytic layouts (areas known in closed form); the IoU
// helper itself on shapes whose overlap is known analytically. The real plans are in
// test_room_inference_plans.cpp.
#include "bim/extraction.hpp"

#include <bimloc/bim/geometry2d.hpp>
#include <bimloc/bim/room_inference.hpp>

#include <Eigen/Geometry>
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <map>

using namespace bimloc::bim;

namespace {

Polygon2 rect(double x0, double y0, double x1, double y1) { return {{x0, y0}, {x1, y0}, {x1, y1}, {x0, y1}}; }

// A straight wall start -> end as the extraction makes it from a box body (wall_faces.cpp).
Wall wall(const std::string& id, Eigen::Vector2d s, Eigen::Vector2d e, double t = 0.2, double h = 2.6, double z0 = 0.0) {
  detail::Extrusion ex;
  const Eigen::Vector2d u = (e - s).normalized(), left(-u.y(), u.x());
  ex.footprint = {s - 0.5 * t * left, e - 0.5 * t * left, e + 0.5 * t * left, s + 0.5 * t * left};
  for (const auto& p : ex.footprint) ex.corners.emplace_back(p.x(), p.y(), z0), ex.corners.emplace_back(p.x(), p.y(), z0 + h);
  ex.z_min = z0, ex.z_max = z0 + h;
  detail::RawProduct p;
  p.global_id = id;
  p.ifc_class = "IfcWall";
  p.extrusion = ex;
  std::string problem;
  auto w = detail::wallFromGeometry(p, problem);
  EXPECT_TRUE(w) << problem;
  return *w;
}

// Four walls of thickness t around the inner rectangle [x0, x1] x [y0, y1], corners overlapping.
std::vector<Wall> box(double x0, double y0, double x1, double y1, double t = 0.2, double z0 = 0.0,
                      const std::string& tag = "") {
  const double h = 0.5 * t;
  return {wall(tag + "S", {x0 - t, y0 - h}, {x1 + t, y0 - h}, t, 2.6, z0),
          wall(tag + "E", {x1 + h, y0 - t}, {x1 + h, y1 + t}, t, 2.6, z0),
          wall(tag + "N", {x1 + t, y1 + h}, {x0 - t, y1 + h}, t, 2.6, z0),
          wall(tag + "W", {x0 - h, y1 + t}, {x0 - h, y0 - t}, t, 2.6, z0)};
}

Storey storeyOf(std::vector<Wall> walls) {
  Storey s;
  s.id = "storey";
  s.name = "test";
  s.walls = std::move(walls);
  return s;
}

Polygon2 rotated(const Polygon2& p, double angle) {
  const Eigen::Rotation2Dd r(angle);
  Polygon2 out;
  for (const auto& v : p) out.push_back(r * v);
  return out;
}

}  // namespace

// --- the IoU helper, on shapes with a known overlap -------------------------------------------

TEST(PolygonIoU, AnalyticShapes) {
  EXPECT_NEAR(polygonIoU(rect(0, 0, 1, 1), rect(0, 0, 1, 1)), 1.0, 1e-9);
  EXPECT_NEAR(polygonIoU(rect(0, 0, 1, 1), rect(0.5, 0, 1.5, 1)), 1.0 / 3.0, 1e-3);  // half overlaps
  EXPECT_NEAR(polygonIoU(rect(0, 0, 1, 1), rect(2, 0, 3, 1)), 0.0, 1e-12);          // apart
  EXPECT_NEAR(polygonIoU(rect(0, 0, 2, 2), {{0, 0}, {2, 0}, {0, 2}}), 0.5, 1e-2);   // triangle inside
  const Polygon2 l_shape = {{0, 0}, {2, 0}, {2, 1}, {1, 1}, {1, 2}, {0, 2}};         // not convex
  EXPECT_NEAR(polygonIoU(l_shape, rect(0, 0, 2, 2)), 0.75, 1e-2);
  // A square and the same square turned by 45 degrees about its centre: a regular octagon,
  // IoU = (8 - 4 sqrt 2) ... = sqrt(2) / 2.
  EXPECT_NEAR(polygonIoU(rect(-1, -1, 1, 1), rotated(rect(-1, -1, 1, 1), M_PI / 4)), std::sqrt(0.5), 5e-3);
  // Orientation does not matter.
  Polygon2 cw = rect(0.5, 0, 1.5, 1);
  std::reverse(cw.begin(), cw.end());
  EXPECT_NEAR(polygonIoU(rect(0, 0, 1, 1), cw), 1.0 / 3.0, 1e-3);
}

// --- analytic layouts ----------------------------------------------------------------------

TEST(RoomInference, FourWallsGiveOneRoomOfTheExactInnerArea) {
  const Storey storey = storeyOf(box(0, 0, 4, 3));
  const InferredRooms inferred = inferRooms(storey);
  ASSERT_EQ(inferred.rooms.size(), 1u);
  const Room& room = inferred.rooms[0];
  EXPECT_EQ(room.source, "inferred");
  EXPECT_NEAR(room.area_m2, 12.0, 1e-6);  // edges snapped onto the faces: exact
  EXPECT_NEAR((room.centre - Eigen::Vector2d(2, 1.5)).norm(), 0.0, 1e-6);
  EXPECT_EQ(room.footprint.size(), 4u);
  EXPECT_GT(signedArea(room.footprint), 0.0);  // counter-clockwise
  EXPECT_GT(polygonIoU(room.footprint, rect(0, 0, 4, 3)), 0.995);
  // Every wall bounds it, by the face looking in.
  ASSERT_EQ(room.walls.size(), 4u);
  for (const auto& rw : room.walls) {
    const Wall* w = storey.findWall(rw.wall_id);
    ASSERT_NE(w, nullptr);
    ASSERT_GE(rw.face, 0);
    EXPECT_GT(w->faces[static_cast<std::size_t>(rw.face)].plane.signedDistance({2, 1.5, 0}), 0.0) << rw.wall_id;
  }
  EXPECT_NEAR(room.floor_z, 0.0, 1e-9);
  EXPECT_NEAR(room.height_m, 2.6, 1e-6);
}

TEST(RoomInference, AWallWithADoorGapSplitsTwoRooms) {
  // Two 4 x 3 rooms side by side; the wall between them at x = 4.1 is two pieces with a 0.9 m gap.
  auto walls = box(0, 0, 8.2, 3);
  walls.push_back(wall("mid-a", {4.1, 0}, {4.1, 1.0}));
  walls.push_back(wall("mid-b", {4.1, 1.9}, {4.1, 3}));
  const InferredRooms inferred = inferRooms(storeyOf(walls));
  ASSERT_EQ(inferred.rooms.size(), 2u);
  const Polygon2 left = rect(0, 0, 4.0, 3), right = rect(4.2, 0, 8.2, 3);
  for (const Polygon2& truth : {left, right}) {
    double best = 0;
    for (const auto& r : inferred.rooms) best = std::max(best, polygonIoU(r.footprint, truth));
    EXPECT_GT(best, 0.97);  // the doorway (0.9 x 0.2 m) is shared between them
  }
}

TEST(RoomInference, AnOpeningWiderThanADoorIsAnOpenPlanNotTwoRooms) {
  auto walls = box(0, 0, 8.2, 3);
  walls.push_back(wall("mid-a", {4.1, 0}, {4.1, 0.5}));
  walls.push_back(wall("mid-b", {4.1, 2.5}, {4.1, 3}));  // 2 m open
  const InferredRooms inferred = inferRooms(storeyOf(walls));
  ASSERT_EQ(inferred.rooms.size(), 1u);
  EXPECT_NEAR(inferred.rooms[0].area_m2, 8.2 * 3 - 2 * 0.5 * 0.2, 0.02);
}

TEST(RoomInference, GapsInTheFacadeKeepTheOutsideOut) {
  // A 12 x 4 m hall whose south façade is five 1.2 m pieces with 1.2 m gaps (windows of a
  // curtain wall at the probe height, or doors), and a U of walls open by 4 m: not a room.
  std::vector<Wall> walls = {wall("E", {12.1, -0.2}, {12.1, 4.2}), wall("N", {12.2, 4.1}, {-0.2, 4.1}),
                             wall("W", {-0.1, 4.2}, {-0.1, -0.2})};
  for (int k = 0; k < 5; ++k) walls.push_back(wall("S" + std::to_string(k), {-0.2 + 2.4 * k, -0.1}, {1.0 + 2.4 * k, -0.1}));
  walls.push_back(wall("U-a", {20, 0}, {20, 4}));
  walls.push_back(wall("U-b", {20, 4}, {24, 4}));
  walls.push_back(wall("U-c", {24, 4}, {24, 0}));
  const InferredRooms inferred = inferRooms(storeyOf(walls));
  ASSERT_EQ(inferred.rooms.size(), 1u);
  // The hall, give or take the window bays up to the façade line.
  EXPECT_GT(polygonIoU(inferred.rooms[0].footprint, rect(0, 0, 12, 4)), 0.97);
}

TEST(RoomInference, CornersThatDoNotQuiteMeetStillClose) {
  // The four walls stop 1 cm short of each other at every corner.
  const double t = 0.2, g = 0.01;
  const std::vector<Wall> walls = {wall("S", {-t, -0.1}, {4 - g, -0.1}), wall("E", {4.1, -t}, {4.1, 3 - g}),
                                   wall("N", {4 + t, 3.1}, {g, 3.1}), wall("W", {-0.1, 3 + t}, {-0.1, g})};
  const InferredRooms inferred = inferRooms(storeyOf(walls));
  ASSERT_EQ(inferred.rooms.size(), 1u);
  EXPECT_NEAR(inferred.rooms[0].area_m2, 12.0, 0.01);
  EXPECT_GT(polygonIoU(inferred.rooms[0].footprint, rect(0, 0, 4, 3)), 0.99);
}

TEST(RoomInference, WallsAtAnAngleGiveTheTurnedRoom) {
  const double angle = 0.5;  // not a multiple of 90 degrees: the raster's staircase is snapped away
  std::vector<Wall> walls;
  const Eigen::Rotation2Dd r(angle);
  for (const auto& w : box(0, 0, 5, 3.5)) walls.push_back(wall(w.id, r * w.start.head<2>(), r * w.end.head<2>()));
  const InferredRooms inferred = inferRooms(storeyOf(walls));
  ASSERT_EQ(inferred.rooms.size(), 1u);
  EXPECT_NEAR(inferred.rooms[0].area_m2, 17.5, 0.01);
  EXPECT_GT(polygonIoU(inferred.rooms[0].footprint, rotated(rect(0, 0, 5, 3.5), angle)), 0.995);
  EXPECT_EQ(inferred.rooms[0].walls.size(), 4u);
}

TEST(RoomInference, CurvedWallFromItsShape) {
  // A 4 m wide room closed by a half-disk wall of inner radius 2 m (its box would fill the room).
  std::vector<Wall> walls = {wall("S", {-2.2, -0.1}, {2.2, -0.1})};
  Polygon2 arc_outer, arc_inner;
  RoomBounds bounds;
  auto& shapes = bounds.shapes;
  const int n = 64;
  for (int k = 0; k <= n; ++k) {
    const double a = M_PI * k / n;
    arc_inner.emplace_back(2.0 * std::cos(a), 2.0 * std::sin(a));
    arc_outer.emplace_back(2.2 * std::cos(a), 2.2 * std::sin(a));
  }
  for (int k = 0; k < n; ++k)  // the wall's body as quads along the arc
    shapes["arc"].push_back({arc_inner[k], arc_inner[k + 1], arc_outer[k + 1], arc_outer[k]});
  Wall arc = wall("arc", {-2.2, 0}, {2.2, 0}, 2.2);  // its fitted box: 4.4 x 2.2
  arc.approximated = true;
  walls.push_back(arc);
  const InferredRooms inferred = inferRooms(storeyOf(walls), {}, bounds);
  ASSERT_EQ(inferred.rooms.size(), 1u);
  EXPECT_NEAR(inferred.rooms[0].area_m2, M_PI * 2.0 * 2.0 / 2.0, 0.1);
}

TEST(RoomInference, OutsideIsNoRoomAndSmallOrThinRegionsAreDroppedByName) {
  auto walls = box(0, 0, 4, 3);
  // A closet of 0.7 x 0.7 m inside, and a 0.3 m wide slot between two parallel walls.
  for (const auto& w : box(1.5, 1.0, 2.2, 1.7, 0.1, 0.0, "closet-")) walls.push_back(w);
  walls.push_back(wall("slot-a", {6, 0}, {10, 0}));
  walls.push_back(wall("slot-b", {6, 0.5}, {10, 0.5}));
  walls.push_back(wall("slot-c", {5.9, -0.1}, {5.9, 0.6}));
  walls.push_back(wall("slot-d", {10.1, -0.1}, {10.1, 0.6}));
  const InferredRooms inferred = inferRooms(storeyOf(walls));
  ASSERT_EQ(inferred.rooms.size(), 1u);  // the room around the closet
  EXPECT_NEAR(inferred.rooms[0].area_m2, 12.0, 0.05);
  std::size_t small = 0, thin = 0;
  for (const auto& w : inferred.warnings) {
    small += w.find("smaller than") != std::string::npos && w.find("storey 'test'") != std::string::npos;
    thin += w.find("too thin") != std::string::npos;
  }
  EXPECT_EQ(small, 1u);
  EXPECT_EQ(thin, 1u);
}

TEST(RoomInference, TwoLevelsInOneStoreyEachGetTheirRooms) {
  // As example.ifc: one storey, walls at z = 0 and z = 3.1, a wall splitting only the upper level.
  auto walls = box(0, 0, 4, 3);
  for (const auto& w : box(0, 0, 4, 3, 0.2, 3.1, "up-")) walls.push_back(w);
  walls.push_back(wall("up-mid", {2.0, 0}, {2.0, 3}, 0.2, 2.6, 3.1));
  // A wall hanging under the roof (starting 2 m above the floor) and a curb bound nothing.
  walls.push_back(wall("gable", {1.0, 0}, {1.0, 3}, 0.2, 0.8, 2.0));
  walls.push_back(wall("curb", {3.0, 0}, {3.0, 3}, 0.2, 0.2, 0.0));
  const InferredRooms inferred = inferRooms(storeyOf(walls));
  ASSERT_EQ(inferred.rooms.size(), 3u);
  std::map<double, std::vector<double>> areas;  // floor -> areas
  for (const auto& r : inferred.rooms) areas[std::round(r.floor_z * 10) / 10].push_back(r.area_m2);
  ASSERT_EQ(areas[0.0].size(), 1u);
  EXPECT_NEAR(areas[0.0][0], 12.0, 1e-6);
  ASSERT_EQ(areas[3.1].size(), 2u);
  EXPECT_NEAR(areas[3.1][0], 5.7, 1e-6);
  EXPECT_NEAR(areas[3.1][1], 5.7, 1e-6);
  // Rooms of the upper level are bounded by the upper walls only.
  for (const auto& r : inferred.rooms)
    for (const auto& rw : r.walls) EXPECT_EQ(rw.wall_id.rfind("up-", 0) == 0, r.floor_z > 1.0) << rw.wall_id;
}

TEST(RoomInference, NoWallsNoRoomsAndTheSameInputGivesTheSameRooms) {
  EXPECT_TRUE(inferRooms(storeyOf({})).rooms.empty());
  EXPECT_TRUE(inferRooms(storeyOf({})).warnings.empty());
  auto walls = box(0, 0, 8.2, 3);
  walls.push_back(wall("mid-a", {4.1, 0}, {4.1, 1.0}));
  walls.push_back(wall("mid-b", {4.1, 1.9}, {4.1, 3}));
  const auto a = inferRooms(storeyOf(walls)), b = inferRooms(storeyOf(walls));
  ASSERT_EQ(a.rooms.size(), b.rooms.size());
  for (std::size_t i = 0; i < a.rooms.size(); ++i) {
    EXPECT_EQ(a.rooms[i].id, b.rooms[i].id);
    ASSERT_EQ(a.rooms[i].footprint.size(), b.rooms[i].footprint.size());
    for (std::size_t k = 0; k < a.rooms[i].footprint.size(); ++k)
      EXPECT_EQ(a.rooms[i].footprint[k], b.rooms[i].footprint[k]);  // bit for bit
  }
}

TEST(RoomInference, AReferenceLevelHoldingTheFacadeIsNotAFloorOfItsOwn) {
  // Ground floor (two rooms), a "top of" reference storey at 0.9 m holding only the façade (as
  // Jesse.1.ifc's "T.O." storeys), and a real first floor at 3 m.
  auto ground_walls = box(0, 0, 8.2, 3);
  ground_walls.push_back(wall("mid", {4.1, 0}, {4.1, 3}));
  std::vector<Storey> storeys = {storeyOf(ground_walls), storeyOf(box(0, 0, 8.2, 3, 0.2, 0.9, "facade-")),
                                 storeyOf(box(0, 0, 8.2, 3, 0.2, 3.0, "first-"))};
  for (auto& w : storeys[1].walls) w.height_m = 5.0;
  for (std::size_t s = 0; s < storeys.size(); ++s) {
    storeys[s].name = "storey " + std::to_string(s);
    storeys[s].id = "S" + std::to_string(s);
    storeys[s].rooms = inferRooms(storeys[s]).rooms;
    ASSERT_EQ(storeys[s].rooms.size(), s == 0 ? 2u : 1u);
  }
  const auto warnings = dropRoomsOfLowerStoreys(storeys);
  EXPECT_EQ(storeys[0].rooms.size(), 2u);
  EXPECT_TRUE(storeys[1].rooms.empty());  // the ground floor's walls stand through it
  EXPECT_EQ(storeys[2].rooms.size(), 1u);  // they end below its probe height
  ASSERT_EQ(warnings.size(), 1u);
  EXPECT_NE(warnings[0].find("storey 'storey 1': inferred room R1"), std::string::npos) << warnings[0];
}
