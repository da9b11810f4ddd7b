// `bimloc extract --out` and `--json`: every file read back by an independent reader
// (nlohmann for JSON, assimp for the meshes, a CSV split for walls.csv).
#include "test_support.hpp"

#include "sim/world/mesh_io.hpp"
#include "sim/world/plan_export.hpp"

#include <bimloc/bim/building_json.hpp>
#include <bimloc/bim/ifc_reader.hpp>

#include <Eigen/Geometry>
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <sstream>

namespace fs = std::filesystem;
using namespace bimloc;

namespace {

std::string slurp(const std::string& path) {
  std::ifstream in(path);
  std::stringstream ss;
  ss << in.rdbuf();
  return ss.str();
}

const std::string kWorld = std::string(BIMLOC_WORLDS_DIR) + "/two_storey.ifc";

}  // namespace

TEST(Export, FilesReadBackAndMatchTheModel) {
  const bim::Building b = bim::readIfc(kWorld);
  const std::string dir = test::tempDir("export") + "/out";
  const auto files = sim::exportPlan(b, dir);
  ASSERT_EQ(files.size(), 2 + b.storeys.size());

  const auto doc = nlohmann::json::parse(slurp(dir + "/building.json"));
  EXPECT_EQ(doc["format"], "bimloc.building");
  EXPECT_EQ(doc["version"], bim::kBuildingJsonVersion);
  const bim::Building back = bim::buildingFromJson(doc);
  ASSERT_EQ(back.storeys.size(), b.storeys.size());
  std::size_t faces = 0;
  for (std::size_t s = 0; s < b.storeys.size(); ++s) {
    ASSERT_EQ(back.storeys[s].walls.size(), b.storeys[s].walls.size());
    ASSERT_EQ(back.storeys[s].rooms.size(), b.storeys[s].rooms.size());
    for (std::size_t w = 0; w < b.storeys[s].walls.size(); ++w)
      for (int f = 0; f < 2; ++f) {
        EXPECT_NEAR(back.storeys[s].walls[w].faces[f].plane.d, b.storeys[s].walls[w].faces[f].plane.d, 1e-9);
        ++faces;
      }
    EXPECT_EQ(back.storeys[s].rooms[0].walls.size(), b.storeys[s].rooms[0].walls.size());

    // The mesh: same triangles, same bounds, through assimp.
    const std::string mesh_file = doc["storeys"][s]["mesh"];
    const bim::TriangleMesh mesh = sim::loadMesh(dir + "/" + mesh_file);
    EXPECT_EQ(mesh.triangles.size(), b.storeys[s].mesh.triangles.size());
    Eigen::AlignedBox3f a, c;
    for (const auto& v : mesh.vertices) a.extend(v);
    for (const auto& v : b.storeys[s].mesh.vertices) c.extend(v);
    EXPECT_NEAR((a.min() - c.min()).norm() + (a.max() - c.max()).norm(), 0.0, 1e-5);
  }

  std::istringstream csv(slurp(dir + "/walls.csv"));
  std::string line;
  std::getline(csv, line);
  EXPECT_EQ(line, "storey,wall_id,face,axis,start_x,start_y,start_z,nx,ny,nz,length_m,thickness_m,d");
  std::size_t rows = 0;
  while (std::getline(csv, line)) {
    ++rows;
    EXPECT_EQ(std::count(line.begin(), line.end(), ','), 12) << line;
  }
  EXPECT_EQ(rows, faces);
}

TEST(Export, JsonSummaryHasTheDocumentedShape) {
  const auto r = test::runBimloc("extract '" + kWorld + "' --json");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const auto j = nlohmann::json::parse(r.out);  // exactly one object: parse fails on trailing text
  EXPECT_EQ(j["file"], kWorld);
  EXPECT_EQ(j["schema"], "IFC4");
  EXPECT_TRUE(j["seconds"].is_number());
  EXPECT_TRUE(j["warnings"].is_array());
  ASSERT_EQ(j["storeys"].size(), 2u);
  for (const auto& s : j["storeys"]) {
    for (const char* key : {"elevation", "rooms", "walls", "wall_planes", "mesh_triangles"})
      EXPECT_TRUE(s[key].is_number()) << key;
    EXPECT_TRUE(s["name"].is_string());
    EXPECT_EQ(s["wall_planes"], 2 * s["walls"].get<int>());
    EXPECT_GT(s["mesh_triangles"], 0);
  }
}

TEST(Export, MeshLoaderRefusesBrokenMeshes) {
  const std::string dir = test::tempDir("mesh");
  std::ofstream(dir + "/nan.obj") << "v 0 0 0\nv 1 0 0\nv nan 1 0\nf 1 2 3\n";
  std::ofstream(dir + "/flat.obj") << "v 0 0 0\nv 1 0 0\nv 2 0 0\nf 1 2 3\n";
  std::ofstream(dir + "/empty.obj") << "# nothing\n";
  EXPECT_THROW(sim::loadMesh(dir + "/nan.obj"), std::runtime_error);
  EXPECT_THROW(sim::loadMesh(dir + "/flat.obj"), std::runtime_error);
  EXPECT_THROW(sim::loadMesh(dir + "/empty.obj"), std::runtime_error);
  EXPECT_THROW(sim::loadMesh(dir + "/missing.ply"), std::runtime_error);
}
