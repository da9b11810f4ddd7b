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
  std::ifstream in(path, std::ios::binary);
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
  // A storey mesh cut short: its faces point past its vertices, which crashed assimp's
  // post-processing (a segfault) before the loader validated the data.
  const auto names = sim::exportPlan(bim::readIfc(std::string(BIMLOC_WORLDS_DIR) + "/site_office.ifc"), dir + "/plan");
  const std::string ply = dir + "/plan/" + names.back();
  const std::string whole = slurp(ply);
  const auto expectRefused = [&](const std::string& bytes, const std::string& problem) {
    std::ofstream(ply, std::ios::binary | std::ios::trunc) << bytes;
    try {
      sim::loadMesh(ply);
      ADD_FAILURE() << "loaded: " << problem;
    } catch (const std::runtime_error& e) {
      EXPECT_NE(std::string(e.what()).find(ply + ": " + problem), std::string::npos) << e.what();
    }
  };
  expectRefused(whole.substr(0, 300), "truncated: element vertex");
  // Without its end_header line, assimp's PLY reader read past its buffer (a segfault too).
  std::string headless = whole;
  headless.erase(headless.find("end_header\n"), 11);
  expectRefused(headless, "not a PLY file (no 'ply' line first, or no end_header line)");
  expectRefused(whole + "x", "1 bytes after the last element");
  // A face of fewer than 3 corners made assimp's triangulation abort the process (an ai_assert;
  // found by the fuzz test with a line deleted from the body). The first face, 3 corners, is
  // rewritten as 2.
  const std::size_t body = whole.find("end_header\n") + 11;
  const std::size_t vertices = std::stoul(whole.substr(whole.find("element vertex ") + 15));
  const std::size_t face = body + vertices * 12;
  ASSERT_EQ(whole[face], '\x03');
  expectRefused(whole.substr(0, face) + '\x02' + whole.substr(face + 1, 8) + whole.substr(face + 13),
                "face 0 has 2 vertex indices; a face needs at least 3");
  // ASCII bodies are walked too.
  const std::string header = "ply\nformat ascii 1.0\nelement vertex 4\nproperty float x\nproperty float y\n"
                             "property float z\nelement face 1\nproperty list uchar int vertex_indices\nend_header\n";
  const std::string corners = "0 0 0\n1 0 0\n1 1 0\n0 1 0\n";
  std::ofstream(ply, std::ios::trunc) << header << corners << "4 0 1 2 3\n";
  EXPECT_EQ(sim::loadMesh(ply).triangles.size(), 2u);  // the square, triangulated
  expectRefused(header + corners + "0\n", "face 0 has 0 vertex indices; a face needs at least 3");
  expectRefused(header + corners + "2 0 1\n", "face 0 has 2 vertex indices; a face needs at least 3");
  expectRefused(header + corners + "3 0 1 4\n", "face 0 names a vertex past the 4 vertices");
  expectRefused(header + corners + "3 0 1\n", "truncated: element face 0 is cut short");
  expectRefused(header + "0 0 0\n1 0 x\n", "element vertex 1: 'x' is not a number");
  expectRefused(header + corners + "3 0 1 2\n7\n", "text after the last element: '7'");
}

// IFC++'s CSG orders faces, and splits them, by heap address: before canonical_mesh.cpp the
// Duplex's Level 2 had 9034 triangles in some runs and 9033 in others, and every FZK-Haus mesh
// held its vertices in another order from run to run. Two extractions in one process (a
// different heap for the second) and one more through the binary must give the same bytes.
TEST(Export, EveryOutputFileIsTheSameBytesOnEveryExtraction) {
  const std::vector<std::string> plans{"AC11-FZK-Haus-IFC.ifc", "AC20-FZK-Haus.ifc", "AC90R1-Jasmin-Sun-105-2x3.ifc",
                                       "Duplex_A_20110907.ifc", "ExampleHOM.ifc",    "Jesse.1.ifc",
                                       "SampleHouse4.ifc",      "example.ifc",       "revit_quantities.ifc"};
  if (test::sharedPlan(plans[0]).empty()) GTEST_SKIP() << "../shared/ifc not found";
  const std::string root = test::tempDir("same-bytes");
  for (const auto& name : plans) {
    const std::string plan = test::sharedPlan(name);
    ASSERT_FALSE(plan.empty()) << name;
    std::vector<std::string> dirs;
    for (int run = 0; run < 2; ++run) {
      dirs.push_back(root + "/" + name + "-" + std::to_string(run));
      sim::exportPlan(bim::readIfc(plan), dirs.back());
    }
    if (name == "Duplex_A_20110907.ifc") {
      dirs.push_back(root + "/" + name + "-binary");
      const auto r = test::runBimloc("extract '" + plan + "' --out '" + dirs.back() + "'");
      ASSERT_EQ(r.exit_code, 0) << r.err;
    }
    std::size_t files = 0;
    for (const auto& entry : fs::directory_iterator(dirs[0])) {
      const std::string file = entry.path().filename().string();
      const std::string first = slurp(entry.path().string());
      for (std::size_t d = 1; d < dirs.size(); ++d)
        EXPECT_TRUE(slurp(dirs[d] + "/" + file) == first) << name << ": " << file << " differs in " << dirs[d];
      ++files;
    }
    EXPECT_GE(files, 3u) << name;
  }
  fs::remove_all(root);
}
