// The project's own worlds: the generator's spec is the truth the extraction must give back
// (round trip: spec -> IFC4 text -> readIfc -> storeys, rooms, walls, faces, topology).
#include "spec_compare.hpp"
#include "test_support.hpp"

#include "sim/worldgen/ifc4_writer.hpp"
#include "sim/worldgen/worlds.hpp"

#include <bimloc/bim/ifc_reader.hpp>

#include <nlohmann/json.hpp>

#include <gtest/gtest.h>

#include <algorithm>
#include <fstream>
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

}  // namespace

TEST_P(World, StoreysRoomsAndWallsCountExactly) { test::expectStoreysMatch(spec_, building_); }

TEST_P(World, EveryWallFaceWithinHalfADegreeAndOneCentimetre) {
  test::expectWallsMatch(spec_, building_, test::SpecTolerance{});
}

TEST_P(World, RoomPolygonsAreasAndTopology) { test::expectRoomsMatch(spec_, building_, test::SpecTolerance{}); }

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
