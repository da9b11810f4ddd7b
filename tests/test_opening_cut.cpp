// Openings cut from a wall's body (localizer/src/bim/openings.cpp, rebuiltBodies): a wall whose
// body is one box extrusion and whose openings are boxes is cut by our exact cutter, not by
// IFC++'s CSG (Carve orders by heap address: on Office_A_20110811.ifc it cut 12 or 14 of one
// wall's 15 windows, a different subset from run to run). Checked against the analytic solid:
// each such wall's part of the storey mesh encloses its box less its openings, and the plan
// read twice gives the same mesh to the byte.
#include "test_support.hpp"

#include <bimloc/bim/ifc_reader.hpp>

#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <string>

using namespace bimloc;

namespace {

// The volume a closed, consistently oriented triangle mesh encloses (divergence theorem).
double enclosedVolume(const bim::Storey& storey, const bim::MeshPart& part) {
  double six_v = 0;
  for (std::uint32_t t = part.first_triangle; t < part.first_triangle + part.triangle_count; ++t) {
    const auto& tri = storey.mesh.triangles[t];
    const Eigen::Vector3d a = storey.mesh.vertices[tri[0]].cast<double>();
    const Eigen::Vector3d b = storey.mesh.vertices[tri[1]].cast<double>();
    const Eigen::Vector3d c = storey.mesh.vertices[tri[2]].cast<double>();
    six_v += a.dot(b.cross(c));
  }
  return std::abs(six_v) / 6.0;
}

// The wall's box less its openings, from the plan's own numbers: every opening of the default
// world's walls (doors, windows) goes through the whole thickness.
double analyticVolume(const bim::Wall& w) {
  double v = w.length_m() * w.thickness_m * w.height_m;
  for (const auto& o : w.faces[0].openings) v -= (o.along_max_m - o.along_min_m) * (o.z_max_m - o.z_min_m) * w.thickness_m;
  return v;
}

}  // namespace

TEST(OpeningCut, EveryWallWithOpeningsEnclosesItsBoxLessItsOpenings) {
  const std::string plan = std::string(BIMLOC_WORLDS_DIR) + "/site_office.ifc";
  const bim::Building building = bim::readIfc(plan);
  const bim::Storey& storey = building.storeys.at(0);
  int checked = 0, openings = 0;
  for (const auto& w : storey.walls) {
    if (w.faces[0].openings.empty() || w.approximated) continue;
    ASSERT_EQ(w.faces[0].openings.size(), w.faces[1].openings.size()) << w.id;
    const bim::MeshPart* part = nullptr;
    for (const auto& p : storey.mesh_parts)
      if (p.id == w.id) part = &p;
    ASSERT_NE(part, nullptr) << w.id;
    // Float vertices a few tens of metres from the origin: about 1e-6 m of rounding each.
    EXPECT_NEAR(enclosedVolume(storey, *part), analyticVolume(w), 1e-4) << w.id << " " << w.name;
    ++checked, openings += static_cast<int>(w.faces[0].openings.size());
  }
  // The corridor's two walls (a door to each office) and the outer walls with windows.
  EXPECT_GE(checked, 4);
  EXPECT_GE(openings, 8);
}

TEST(OpeningCut, ThePlanReadTwiceGivesTheSameMeshToTheByte) {
  const std::string plan = std::string(BIMLOC_WORLDS_DIR) + "/site_office.ifc";
  const bim::Building a = bim::readIfc(plan), b = bim::readIfc(plan);
  ASSERT_EQ(a.storeys.size(), b.storeys.size());
  for (std::size_t s = 0; s < a.storeys.size(); ++s) {
    const auto& ma = a.storeys[s].mesh;
    const auto& mb = b.storeys[s].mesh;
    ASSERT_EQ(ma.vertices.size(), mb.vertices.size());
    ASSERT_EQ(ma.triangles.size(), mb.triangles.size());
    EXPECT_EQ(0, std::memcmp(ma.vertices.data(), mb.vertices.data(), ma.vertices.size() * sizeof(ma.vertices[0])));
    EXPECT_EQ(0, std::memcmp(ma.triangles.data(), mb.triangles.data(), ma.triangles.size() * sizeof(ma.triangles[0])));
  }
}
