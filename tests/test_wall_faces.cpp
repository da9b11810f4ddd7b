// Wall faces and room topology from plain geometry, against analytic truth.
#include "bim/extraction.hpp"

#include <gtest/gtest.h>

#include <cmath>

using namespace bimloc::bim;
using namespace bimloc::bim::detail;

namespace {

// A box wall start→end, thickness t, height h, as the triangle mesh IFC++ would give.
RawProduct boxWall(Eigen::Vector2d s, Eigen::Vector2d e, double t, double h, double z0 = 0.0) {
  Extrusion ex;
  const Eigen::Vector2d u = (e - s).normalized(), left(-u.y(), u.x());
  ex.footprint = {s - 0.5 * t * left, e - 0.5 * t * left, e + 0.5 * t * left, s + 0.5 * t * left};
  for (const auto& p : ex.footprint) {
    ex.corners.emplace_back(p.x(), p.y(), z0);
    ex.corners.emplace_back(p.x(), p.y(), z0 + h);
  }
  ex.z_min = z0, ex.z_max = z0 + h;
  RawProduct p;
  p.global_id = "wall";
  p.ifc_class = "IfcWall";
  p.mesh = prismMesh(ex);
  return p;
}

}  // namespace

TEST(WallFaces, BoxWallAtAnAngleGivesItsTwoFacesExactly) {
  const Eigen::Vector2d s(1, 2), e(1 + 4 * std::cos(0.5), 2 + 4 * std::sin(0.5));
  std::string problem;
  const auto wall = wallFromGeometry(boxWall(s, e, 0.24, 2.6, 3.0), problem);
  ASSERT_TRUE(wall);
  EXPECT_TRUE(problem.empty()) << problem;
  EXPECT_NEAR(wall->thickness_m, 0.24, 1e-5);
  EXPECT_NEAR(wall->height_m, 2.6, 1e-5);
  EXPECT_NEAR(wall->length_m(), 4.0, 1e-5);
  EXPECT_NEAR(wall->start.z(), 3.0, 1e-5);
  const Eigen::Vector3d mid(0.5 * (s + e).x(), 0.5 * (s + e).y(), 3.0);
  for (const auto& face : wall->faces) {
    EXPECT_NEAR(face.plane.n.norm(), 1.0, 1e-12);
    EXPECT_NEAR(face.plane.n.z(), 0.0, 1e-12);
    // The face is 0.12 m from the axis, and the normal points away from it (out of the wall).
    EXPECT_NEAR(face.plane.signedDistance(mid), -0.12, 1e-5);
    EXPECT_NEAR(face.plane.signedDistance(face.start), 0.0, 1e-9);  // paper Eq. 1
    EXPECT_NEAR(face.length_m(), 4.0, 1e-5);
  }
  EXPECT_NEAR(wall->faces[0].plane.n.dot(wall->faces[1].plane.n), -1.0, 1e-12);
  // Paper Eq. 2, in our sign convention: d' = -d - thickness.
  EXPECT_NEAR(wall->faces[1].plane.d, -wall->faces[0].plane.d - wall->thickness_m, 1e-5);
  EXPECT_EQ(wall->faces[0].axis, WallAxis::Y);  // normal mostly along y at 0.5 rad
}

TEST(WallFaces, AxisClassFollowsTheDominantNormalComponent) {
  std::string problem;
  const auto along_x = wallFromGeometry(boxWall({0, 0}, {5, 0}, 0.2, 2.5), problem);
  const auto along_y = wallFromGeometry(boxWall({0, 0}, {0, 5}, 0.2, 2.5), problem);
  ASSERT_TRUE(along_x && along_y);
  EXPECT_EQ(along_x->faces[0].axis, WallAxis::Y);
  EXPECT_EQ(along_y->faces[0].axis, WallAxis::X);
}

TEST(WallFaces, CurvedWallIsApproximatedAndSaysSo) {
  RawProduct p;
  p.global_id = "arc";
  p.ifc_class = "IfcWall";
  for (int i = 0; i <= 16; ++i) {  // a quarter circle of radius 3, 0.2 thick
    const double a = M_PI / 2 * i / 16;
    for (double r : {2.9, 3.1})
      for (double z : {0.0, 2.5}) p.mesh.vertices.emplace_back(r * std::cos(a), r * std::sin(a), z);
  }
  p.mesh.triangles.push_back({0, 1, 2});
  std::string problem;
  const auto wall = wallFromGeometry(p, problem);
  ASSERT_TRUE(wall);
  EXPECT_TRUE(wall->approximated);
  EXPECT_NE(problem.find("approximated"), std::string::npos);
}

TEST(WallFaces, NoGeometryIsReportedNotThrown) {
  RawProduct p;
  p.geometry_problem = "no extruded solid in its Body representation";
  std::string problem;
  EXPECT_FALSE(wallFromGeometry(p, problem));
  EXPECT_EQ(problem, p.geometry_problem);
}

TEST(Topology, GeometricAdjacencyFindsTheFacesLookingIntoAnLShapedRoom) {
  // L-shaped room bounded by six walls, 0.2 m thick, faces exactly on the footprint.
  const std::vector<Eigen::Vector2d> room = {{0, 0}, {6, 0}, {6, 3}, {3, 3}, {3, 6}, {0, 6}};
  Storey storey;
  for (std::size_t i = 0; i < room.size(); ++i) {
    const Eigen::Vector2d a = room[i], b = room[(i + 1) % room.size()];
    const Eigen::Vector2d out = -Eigen::Vector2d(-(b - a).y(), (b - a).x()).normalized();  // away from the room
    std::string problem;
    auto wall = wallFromGeometry(boxWall(a + 0.1 * out, b + 0.1 * out, 0.2, 2.5), problem);
    ASSERT_TRUE(wall);
    wall->id = "w" + std::to_string(i);
    storey.walls.push_back(*wall);
  }
  // A wall elsewhere, parallel to an edge but 2 m away: must not be linked.
  std::string problem;
  auto far = wallFromGeometry(boxWall({0, -2}, {6, -2}, 0.2, 2.5), problem);
  far->id = "far";
  storey.walls.push_back(*far);
  Room r;
  r.id = "L";
  r.footprint = room;
  storey.rooms.push_back(r);
  linkRoomsToWalls(storey, {}, ExtractOptions{});
  const auto& linked = storey.rooms[0].walls;
  ASSERT_EQ(linked.size(), 6u);
  EXPECT_EQ(storey.rooms[0].topology_source, "geometry");
  for (const auto& rw : linked) {
    const Wall* w = storey.findWall(rw.wall_id);
    ASSERT_NE(w, nullptr);
    ASSERT_GE(rw.face, 0);
    // The linked face looks into the room: the room's area centroid region is in front.
    const auto& face = w->faces[static_cast<std::size_t>(rw.face)];
    EXPECT_GT(face.plane.signedDistance(Eigen::Vector3d(1.5, 1.5, 0)), 0.0) << rw.wall_id;
  }
}

TEST(Topology, SpaceBoundariesWinOverGeometryWhereTheFileHasThem) {
  Storey storey;
  std::string problem;
  auto w = wallFromGeometry(boxWall({0, -0.1}, {4, -0.1}, 0.2, 2.5), problem);
  w->id = "south";
  storey.walls.push_back(*w);
  Room r;
  r.id = "room";
  r.footprint = {{0, 0}, {4, 0}, {4, 4}, {0, 4}};
  r.centre = {2, 2};
  storey.rooms.push_back(r);
  linkRoomsToWalls(storey, {{"room", "south"}, {"room", "a-door"}, {"other", "south"}}, ExtractOptions{});
  ASSERT_EQ(storey.rooms[0].walls.size(), 1u);
  EXPECT_EQ(storey.rooms[0].topology_source, "IfcRelSpaceBoundary");
  const auto& face = storey.walls[0].faces[static_cast<std::size_t>(storey.rooms[0].walls[0].face)];
  EXPECT_NEAR(face.plane.n.y(), 1.0, 1e-9);  // the face looking north, into the room
}
