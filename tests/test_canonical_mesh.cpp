// canonicalSurface: the same surface, however it was cut into triangles, gives the same bytes,
// and keeps the surface (area, and rays against analytic truth).
#include "test_support.hpp"

#include "bim/extraction.hpp"
#include "sim/world/mesh_io.hpp"
#include "sim/world/world.hpp"

#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <map>

using namespace bimloc;

namespace {

// A wall face in the plane y = 0: the rectangle [0, 4] x [0, 3] (x, z) with a window hole
// [1, 2] x [1, 2], as triangles of corner names.
const std::map<char, Eigen::Vector3f> kCorners{
    {'a', {0, 0, 0}}, {'b', {4, 0, 0}}, {'c', {4, 0, 3}}, {'d', {0, 0, 3}}, {'e', {1, 0, 1}},  {'f', {2, 0, 1}},
    {'g', {2, 0, 2}}, {'h', {1, 0, 2}}, {'m', {3, 0, 0}}, {'p', {1, 0, 0.5f}}};

// Every triangle with its own three vertices (nothing shared), in the order given.
bim::TriangleMesh soup(const std::vector<std::string>& triangles) {
  bim::TriangleMesh m;
  for (const auto& t : triangles) {
    const auto base = static_cast<std::uint32_t>(m.vertices.size());
    for (char c : t) m.vertices.push_back(kCorners.at(c));
    m.triangles.push_back({base, base + 1, base + 2});
  }
  return m;
}

double area(const bim::TriangleMesh& m) {
  double sum = 0.0;
  for (const auto& t : m.triangles)
    sum += 0.5 * (m.vertices[t[1]] - m.vertices[t[0]]).cross(m.vertices[t[2]] - m.vertices[t[0]]).cast<double>().norm();
  return sum;
}

}  // namespace

TEST(CanonicalMesh, TheSameFaceCutTwoWaysGivesTheSameBytes) {
  // Conforming: eight triangles around the hole.
  auto one = soup({"abf", "afe", "bcg", "bgf", "cdh", "chg", "dae", "deh"});
  // The same face split at other points: "abf" at m (a corner that goes straight on), "afe"
  // at p on its edge a-f (a T-junction: "amf" keeps the whole edge), a zero-area triangle,
  // other corner orders, another order of triangles.
  auto two = soup({"hde", "cdh", "gch", "fbg", "gbc", "ape", "pfe", "amf", "mbf", "amb", "eda"});
  bim::detail::canonicalSurface(one);
  bim::detail::canonicalSurface(two);
  EXPECT_EQ(one.vertices, two.vertices);
  EXPECT_EQ(one.triangles, two.triangles);
  EXPECT_NEAR(area(one), 4 * 3 - 1, 1e-5);
  EXPECT_NEAR(area(two), 4 * 3 - 1, 1e-5);
  // Every triangle faces the way the face did (-y).
  for (const auto& t : one.triangles)
    EXPECT_LT((one.vertices[t[1]] - one.vertices[t[0]]).cross(one.vertices[t[2]] - one.vertices[t[0]]).y(), 0.0f);

  // Rays across the face on a grid: through the hole, onto the face elsewhere.
  const std::string path = test::tempDir("canonical") + "/face.ply";
  sim::writeMesh(one, path);
  const sim::World world = sim::World::fromMesh(path);
  for (int ix = 1; ix < 80; ++ix)
    for (int iz = 1; iz < 60; ++iz) {
      const float x = 0.05f * ix, z = 0.05f * iz;
      const bool near_edge = std::abs(x - 1) < 0.01f || std::abs(x - 2) < 0.01f || std::abs(z - 1) < 0.01f ||
                             std::abs(z - 2) < 0.01f;
      if (near_edge) continue;
      const bool in_hole = x > 1 && x < 2 && z > 1 && z < 2;
      const auto hit = world.castRay(0, {x, -1.0f, z}, {0, 1, 0}, 0.0f, 5.0f);
      EXPECT_EQ(hit.hit(), !in_hole) << x << " " << z;
      if (hit.hit()) {
        EXPECT_NEAR(hit.range_m, 1.0f, 1e-5f);
      }
    }
}

TEST(CanonicalMesh, AClosedBoxStaysClosed) {
  // A unit box, each face as two triangles (outward), with shared vertices.
  bim::TriangleMesh box;
  for (int i = 0; i < 8; ++i) box.vertices.emplace_back(i & 1, (i >> 1) & 1, (i >> 2) & 1);
  box.triangles = {{0, 2, 3}, {0, 3, 1}, {4, 5, 7}, {4, 7, 6}, {0, 1, 5}, {0, 5, 4},
                   {2, 6, 7}, {2, 7, 3}, {0, 4, 6}, {0, 6, 2}, {1, 3, 7}, {1, 7, 5}};
  bim::detail::canonicalSurface(box);
  ASSERT_EQ(box.triangles.size(), 12u);
  EXPECT_EQ(box.vertices.size(), 8u);
  std::map<std::pair<std::uint32_t, std::uint32_t>, int> edges;
  for (const auto& t : box.triangles)
    for (int k = 0; k < 3; ++k) ++edges[{t[k], t[(k + 1) % 3]}];
  for (const auto& [e, n] : edges) {
    EXPECT_EQ(n, 1);
    EXPECT_EQ(edges.count({e.second, e.first}), 1u);
  }
  EXPECT_NEAR(area(box), 6.0, 1e-6);
}
