// The project's own worlds: the generator's spec is the truth the extraction must give back
// (round trip: spec -> IFC4 text -> readIfc -> storeys, rooms, walls, faces, topology).
#include "test_support.hpp"

#include "sim/worldgen/ifc4_writer.hpp"
#include "sim/worldgen/worlds.hpp"

#include <bimloc/bim/geometry2d.hpp>
#include <bimloc/bim/ifc_reader.hpp>

#include <nlohmann/json.hpp>

#include <gtest/gtest.h>

#include <cmath>
#include <fstream>
#include <set>
#include <sstream>

using namespace bimloc;

namespace {

class World : public ::testing::TestWithParam<std::string> {
 protected:
  void SetUp() override {
    spec_ = worldgen::makeWorld(GetParam());
    path_ = test::tempDir("world") + "/" + GetParam() + ".ifc";
    std::ofstream(path_) << worldgen::writeIfc4(spec_);
    building_ = bim::readIfc(path_);
  }
  worldgen::WorldSpec spec_;
  std::string path_;
  bim::Building building_;
};

double angleDeg(const Eigen::Vector3d& a, const Eigen::Vector3d& b) {
  return std::acos(std::clamp(a.normalized().dot(b.normalized()), -1.0, 1.0)) * 180.0 / M_PI;
}

}  // namespace

TEST_P(World, StoreysRoomsAndWallsCountExactly) {
  EXPECT_TRUE(building_.warnings.empty()) << building_.warnings.front();
  ASSERT_EQ(building_.storeys.size(), spec_.storeys.size());
  for (std::size_t s = 0; s < spec_.storeys.size(); ++s) {
    EXPECT_NEAR(building_.storeys[s].elevation_m, spec_.storeys[s].elevation_m, 1e-9);
    EXPECT_EQ(building_.storeys[s].walls.size(), spec_.storeys[s].walls.size());
    EXPECT_EQ(building_.storeys[s].rooms.size(), spec_.storeys[s].rooms.size());
    EXPECT_GT(building_.storeys[s].mesh.triangles.size(), 0u);
  }
}

TEST_P(World, EveryWallFaceWithinHalfADegreeAndOneCentimetre) {
  for (std::size_t s = 0; s < spec_.storeys.size(); ++s)
    for (std::size_t w = 0; w < spec_.storeys[s].walls.size(); ++w) {
      const auto& ws = spec_.storeys[s].walls[w];
      const bim::Wall* wall = building_.storeys[s].findWall(worldgen::wallGlobalId(spec_, s, w));
      ASSERT_NE(wall, nullptr) << ws.name;
      EXPECT_NEAR(wall->thickness_m, ws.thickness_m, 1e-6) << ws.name;  // exact
      EXPECT_NEAR(wall->height_m, ws.height_m, 1e-4) << ws.name;
      EXPECT_FALSE(wall->approximated) << ws.name;
      // The axis, either way round.
      const Eigen::Vector2d a = wall->start.head<2>(), b = wall->end.head<2>();
      EXPECT_LT(std::min((a - ws.start).norm() + (b - ws.end).norm(), (a - ws.end).norm() + (b - ws.start).norm()),
                0.01)
          << ws.name;
      // Both faces of the generator: the axis offset by +-thickness/2, normals pointing out.
      const Eigen::Vector2d u = (ws.end - ws.start).normalized(), left(-u.y(), u.x());
      for (const double side : {1.0, -1.0}) {
        const Eigen::Vector3d n(side * left.x(), side * left.y(), 0.0);
        const Eigen::Vector2d on = ws.start + side * 0.5 * ws.thickness_m * left;
        const double d = -n.head<2>().dot(on);
        const bim::WallFace* match = nullptr;
        for (const auto& f : wall->faces)
          if (angleDeg(f.plane.n, n) < 0.5) match = &f;
        ASSERT_NE(match, nullptr) << ws.name;
        EXPECT_LT(std::abs(match->plane.d - d), 0.01) << ws.name;
        EXPECT_EQ(match->axis, std::abs(n.x()) >= std::abs(n.y()) ? bim::WallAxis::X : bim::WallAxis::Y);
      }
    }
}

TEST_P(World, RoomPolygonsAreasAndTopology) {
  for (std::size_t s = 0; s < spec_.storeys.size(); ++s) {
    const auto& storey = building_.storeys[s];
    for (std::size_t r = 0; r < spec_.storeys[s].rooms.size(); ++r) {
      const auto& rs = spec_.storeys[s].rooms[r];
      const bim::Room* room = storey.findRoom(worldgen::spaceGlobalId(spec_, s, r));
      ASSERT_NE(room, nullptr) << rs.name;
      EXPECT_EQ(room->name, rs.name);
      EXPECT_EQ(room->long_name, rs.long_name);
      const bim::Polygon2 expected = bim::simplifyPolygon(rs.footprint);
      EXPECT_NEAR(room->area_m2, std::abs(bim::signedArea(expected)), 1e-4) << rs.name;
      ASSERT_EQ(room->footprint.size(), expected.size()) << rs.name;
      for (const auto& v : expected) {
        double nearest = 1e9;
        for (const auto& p : room->footprint) nearest = std::min(nearest, (p - v).norm());
        EXPECT_LT(nearest, 0.01) << rs.name;
      }
      EXPECT_LT((room->centre - bim::areaCentroid(expected)).norm(), 0.01) << rs.name;
      EXPECT_EQ(room->topology_source, spec_.space_boundaries ? "IfcRelSpaceBoundary" : "geometry") << rs.name;
      std::set<std::string> expected_walls, got_walls;
      for (int w : rs.walls) expected_walls.insert(worldgen::wallGlobalId(spec_, s, static_cast<std::size_t>(w)));
      for (const auto& rw : room->walls) {
        got_walls.insert(rw.wall_id);
        ASSERT_GE(rw.face, 0) << rs.name;
        // The linked face looks into the room: a footprint edge lies on it.
        const auto& face = storey.findWall(rw.wall_id)->faces[static_cast<std::size_t>(rw.face)];
        double on_face = 1e9;
        for (const auto& p : room->footprint)
          on_face = std::min(on_face, std::abs(face.plane.signedDistance(Eigen::Vector3d(p.x(), p.y(), 0))));
        EXPECT_LT(on_face, 0.01) << rs.name << " / " << rw.wall_id;
      }
      EXPECT_EQ(got_walls, expected_walls) << rs.name;
    }
  }
}

INSTANTIATE_TEST_SUITE_P(Generated, World, ::testing::ValuesIn(worldgen::worldNames()));

TEST(Worlds, CommittedFilesAreWhatTheGeneratorWrites) {
  for (const auto& name : worldgen::worldNames()) {
    std::ifstream in(std::string(BIMLOC_WORLDS_DIR) + "/" + name + ".ifc");
    ASSERT_TRUE(in) << name << ".ifc is missing from worlds/: run 'bimloc worldgen --all --out worlds'";
    std::stringstream ss;
    ss << in.rdbuf();
    EXPECT_EQ(ss.str(), worldgen::writeIfc4(worldgen::makeWorld(name)))
        << name << ".ifc is stale: run 'bimloc worldgen --all --out worlds'";
  }
}

TEST(Worlds, GeneratorIsDeterministicAndHasTheDefaultWorld) {
  const auto names = worldgen::worldNames();
  EXPECT_NE(std::find(names.begin(), names.end(), worldgen::kDefaultWorld), names.end());
  EXPECT_GE(names.size(), 3u);
  for (const auto& name : names) EXPECT_EQ(worldgen::writeIfc4(worldgen::makeWorld(name)), worldgen::writeIfc4(worldgen::makeWorld(name)));
  EXPECT_THROW(worldgen::makeWorld("no_such_world"), std::invalid_argument);
}

TEST(Worlds, CommittedMeshesAreWhatExtractionGives) {
  for (const auto& name : worldgen::worldNames()) {
    std::ifstream in(std::string(BIMLOC_WORLDS_DIR) + "/../meshes/" + name + "/building.json");
    ASSERT_TRUE(in) << "meshes/" << name << " is missing: run 'make meshes'";
    const auto doc = nlohmann::json::parse(in);
    const bim::Building b = bim::readIfc(std::string(BIMLOC_WORLDS_DIR) + "/" + name + ".ifc");
    ASSERT_EQ(doc["storeys"].size(), b.storeys.size()) << name;
    for (std::size_t s = 0; s < b.storeys.size(); ++s) {
      EXPECT_EQ(doc["storeys"][s]["mesh_triangles"], b.storeys[s].mesh.triangles.size()) << name << ": run 'make meshes'";
      EXPECT_EQ(doc["storeys"][s]["walls"].size(), b.storeys[s].walls.size()) << name;
    }
  }
}

TEST(Worlds, SimulatorMeshesLeaveDoorLeavesOut) {
  // `bimloc extract` keeps every physical element; the simulator's world has doorways instead
  // of doors, so that a base can walk out of the rooms of real plans (closed leaves in the mesh).
  const std::string plan = std::string(BIMLOC_WORLDS_DIR) + "/site_office.ifc";
  bim::ExtractOptions without;
  without.door_leaves = false;
  const auto all = bim::readIfc(plan), doorless = bim::readIfc(plan, without);
  EXPECT_LT(doorless.storeys[0].mesh.triangles.size(), all.storeys[0].mesh.triangles.size());
  EXPECT_EQ(doorless.storeys[0].walls.size(), all.storeys[0].walls.size());
}
