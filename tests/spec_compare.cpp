#include "spec_compare.hpp"

#include "sim/worldgen/ifc4_writer.hpp"

#include <bimloc/bim/geometry2d.hpp>

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <set>

namespace bimloc::test {
namespace {

double angleDeg(const Eigen::Vector3d& a, const Eigen::Vector3d& b) {
  return std::acos(std::clamp(a.normalized().dot(b.normalized()), -1.0, 1.0)) * 180.0 / M_PI;
}

}  // namespace

void expectStoreysMatch(const worldgen::WorldSpec& spec, const bim::Building& building) {
  EXPECT_TRUE(building.warnings.empty()) << spec.name << ": " << building.warnings.front();
  ASSERT_EQ(building.storeys.size(), spec.storeys.size()) << spec.name;
  for (std::size_t s = 0; s < spec.storeys.size(); ++s) {
    EXPECT_NEAR(building.storeys[s].elevation_m, spec.storeys[s].elevation_m, 1e-9) << spec.name;
    EXPECT_EQ(building.storeys[s].walls.size(), spec.storeys[s].walls.size()) << spec.name;
    EXPECT_EQ(building.storeys[s].rooms.size(), spec.storeys[s].rooms.size()) << spec.name;
    EXPECT_GT(building.storeys[s].mesh.triangles.size(), 0u) << spec.name;
  }
}

void expectWallsMatch(const worldgen::WorldSpec& spec, const bim::Building& building, const SpecTolerance& tol) {
  ASSERT_EQ(building.storeys.size(), spec.storeys.size()) << spec.name;
  for (std::size_t s = 0; s < spec.storeys.size(); ++s)
    for (std::size_t w = 0; w < spec.storeys[s].walls.size(); ++w) {
      const auto& ws = spec.storeys[s].walls[w];
      const std::string at = spec.name + " " + ws.name;
      const bim::Wall* wall = building.storeys[s].findWall(worldgen::wallGlobalId(spec, s, w));
      ASSERT_NE(wall, nullptr) << at;
      EXPECT_NEAR(wall->thickness_m, ws.thickness_m, tol.thickness_m) << at;
      EXPECT_NEAR(wall->height_m, ws.height_m, 1e-4) << at;
      EXPECT_FALSE(wall->approximated) << at;
      // The axis, either way round.
      const Eigen::Vector2d a = wall->start.head<2>(), b = wall->end.head<2>();
      EXPECT_LT(std::min((a - ws.start).norm() + (b - ws.end).norm(), (a - ws.end).norm() + (b - ws.start).norm()),
                tol.axis_m)
          << at;
      // Both faces of the generator: the axis offset by +-thickness/2, normals pointing out.
      const Eigen::Vector2d u = (ws.end - ws.start).normalized(), left(-u.y(), u.x());
      for (const double side : {1.0, -1.0}) {
        const Eigen::Vector3d n(side * left.x(), side * left.y(), 0.0);
        const Eigen::Vector2d on = ws.start + side * 0.5 * ws.thickness_m * left;
        const double d = -n.head<2>().dot(on);
        const bim::WallFace* match = nullptr;
        for (const auto& f : wall->faces)
          if (angleDeg(f.plane.n, n) < 0.5) match = &f;
        ASSERT_NE(match, nullptr) << at;
        EXPECT_LT(std::abs(match->plane.d - d), tol.face_m) << at;
        EXPECT_EQ(match->axis, std::abs(n.x()) >= std::abs(n.y()) ? bim::WallAxis::X : bim::WallAxis::Y) << at;
      }
    }
}

void expectRoomsMatch(const worldgen::WorldSpec& spec, const bim::Building& building, const SpecTolerance& tol) {
  ASSERT_EQ(building.storeys.size(), spec.storeys.size()) << spec.name;
  for (std::size_t s = 0; s < spec.storeys.size(); ++s) {
    const auto& storey = building.storeys[s];
    for (std::size_t r = 0; r < spec.storeys[s].rooms.size(); ++r) {
      const auto& rs = spec.storeys[s].rooms[r];
      const std::string at = spec.name + " " + rs.name;
      const bim::Room* room = storey.findRoom(worldgen::spaceGlobalId(spec, s, r));
      ASSERT_NE(room, nullptr) << at;
      EXPECT_EQ(room->name, rs.name);
      EXPECT_EQ(room->long_name, rs.long_name);
      const bim::Polygon2 expected = bim::simplifyPolygon(rs.footprint);
      EXPECT_NEAR(room->area_m2, std::abs(bim::signedArea(expected)), tol.area_m2) << at;
      ASSERT_EQ(room->footprint.size(), expected.size()) << at;
      for (const auto& v : expected) {
        double nearest = 1e9;
        for (const auto& p : room->footprint) nearest = std::min(nearest, (p - v).norm());
        EXPECT_LT(nearest, tol.vertex_m) << at;
      }
      EXPECT_LT((room->centre - bim::areaCentroid(expected)).norm(), tol.vertex_m) << at;
      EXPECT_EQ(room->topology_source, spec.space_boundaries ? "IfcRelSpaceBoundary" : "geometry") << at;
      std::set<std::string> expected_walls, got_walls;
      for (int w : rs.walls) expected_walls.insert(worldgen::wallGlobalId(spec, s, static_cast<std::size_t>(w)));
      for (const auto& rw : room->walls) {
        got_walls.insert(rw.wall_id);
        ASSERT_GE(rw.face, 0) << at;
        // The linked face looks into the room: a footprint edge lies on it.
        const auto& face = storey.findWall(rw.wall_id)->faces[static_cast<std::size_t>(rw.face)];
        double on_face = 1e9;
        for (const auto& p : room->footprint)
          on_face = std::min(on_face, std::abs(face.plane.signedDistance(Eigen::Vector3d(p.x(), p.y(), 0))));
        EXPECT_LT(on_face, tol.vertex_m) << at << " / " << rw.wall_id;
      }
      EXPECT_EQ(got_walls, expected_walls) << at;
    }
  }
}

}  // namespace bimloc::test
